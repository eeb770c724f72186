#!/usr/bin/env python3
"""Writes the binary seed inputs of test/fuzz/corpus/ (the text ones are plain files there).

Run from anywhere: /usr/bin/python3 test/fuzz/make_seeds.py. Deterministic; re-running rewrites
the same files.
"""
import math
import pathlib
import struct

CORPUS = pathlib.Path(__file__).resolve().parent / "corpus"
FLOAT32, FLOAT64, UINT16 = 7, 8, 4


def write(target, name, data):
    (CORPUS / target / name).write_bytes(data)


# --- initial_transform: the list of numbers, 8 bytes (a little-endian double) each ----------
def doubles(*values):
    return b"".join(struct.pack("<d", v) for v in values)


write("initial_transform", "xyz_rpy", doubles(1.0, 2.0, 0.5, 0.0, 0.0, 0.3))
write("initial_transform", "xyz_quaternion", doubles(1.0, 2.0, 0.5, 0.0, 0.0, 0.2, 0.98))
write("initial_transform", "matrix_4x4",
      doubles(0, -1, 0, 1.5, 1, 0, 0, -0.8, 0, 0, 1, 0.1, 0, 0, 0, 1))
write("initial_transform", "zero_quaternion", doubles(0, 0, 0, 0, 0, 0, 0))
write("initial_transform", "nan", doubles(math.nan, 0, 0, 0, 0, 0))
write("initial_transform", "five_numbers", doubles(1, 2, 3, 4, 5))


# --- command_line: argv words separated by NUL bytes ----------------------------------------
def argv(*words):
    return b"\0".join(w.encode() for w in words)


write("command_line", "align", argv("--target", "t.pcd", "--source", "s.pcd", "--k", "10",
                                    "--nu=inf", "--radius", "0.5", "--solver", "ceres"))
write("command_line", "all_numbers", argv(
    "--runs", "20", "--em-iterations", "7", "--fixed-sigma", "0.01", "--sigma-mode", "fixed",
    "--threads", "2", "--source-voxel", "0.05", "--target-voxel", "0", "--translation-epsilon",
    "1e-5", "--rotation-epsilon", "1e-5", "--min-correspondences", "30", "--max-iterations",
    "50", "--ndt-resolution", "1.0", "--ndt-step-size", "0.1", "--anisotropy", "1",
    "--normal-voxel", "0.15", "--solver-iterations", "2", "--coarse-stride", "3",
    "--ndt-epsilon", "1e-6", "--min-radius", "0.2", "--repeat", "5"))
write("command_line", "grid_lists", argv("--k", "1,5,10", "--nu", "3,5,inf", "--radius=0.5,1"))
write("command_line", "bad_values", argv("--k", "ten", "--nu", "nan", "--radius", "-1"))
write("command_line", "unknown_flag", argv("--bogus", "1", "stray"))
write("command_line", "missing_value", argv("--help", "--k"))


# --- point_cloud2 (wire mode): first byte odd, then a serialized sensor_msgs/PointCloud2 ------
def ros_string(text):
    data = text.encode()
    return struct.pack("<I", len(data)) + data


def point_field(name, offset, datatype, count=1):
    return ros_string(name) + struct.pack("<IBI", offset, datatype, count)


def point_cloud2(height, width, fields, point_step, row_step, data, bigendian=0):
    header = struct.pack("<III", 7, 100, 0) + ros_string("map")
    return (b"\x01" + header + struct.pack("<II", height, width) +
            struct.pack("<I", len(fields)) + b"".join(fields) +
            struct.pack("<BII", bigendian, point_step, row_step) +
            struct.pack("<I", len(data)) + data + b"\x01")


XYZ32 = [point_field("x", 0, FLOAT32), point_field("y", 4, FLOAT32), point_field("z", 8, FLOAT32)]
points = [(0.1 * i, -0.2 * i, 1.0 + 0.01 * i) for i in range(4)]
packed = b"".join(struct.pack("<fff", *p) for p in points)
write("point_cloud2", "wire_xyz_float32", point_cloud2(1, 4, XYZ32, 12, 48, packed))
with_intensity = XYZ32 + [point_field("intensity", 12, FLOAT32), point_field("ring", 16, UINT16)]
padded = b"".join(struct.pack("<ffffHxx", *p, 5.0, 3) for p in points)
write("point_cloud2", "wire_xyzi_ring_organised",
      point_cloud2(2, 2, with_intensity, 20, 40, padded))
doubles_xyz = [point_field("x", 0, FLOAT64), point_field("y", 8, FLOAT64),
               point_field("z", 16, FLOAT64)]
with_nan = b"".join(struct.pack("<ddd", *p) for p in points[:2]) + struct.pack(
    "<ddd", math.nan, 0, 0)
write("point_cloud2", "wire_xyz_float64_with_nan", point_cloud2(1, 3, doubles_xyz, 24, 72,
                                                                 with_nan))
write("point_cloud2", "wire_truncated_data", point_cloud2(1, 4, XYZ32, 12, 48, packed[:40]))
write("point_cloud2", "wire_no_z", point_cloud2(1, 4, XYZ32[:2], 12, 48, packed))
write("point_cloud2", "wire_big_endian", point_cloud2(1, 4, XYZ32, 12, 48, packed, bigendian=1))
