# Shared by the entry points in scripts/: paths, the Debian-python PATH fix and the catkin build.
# Source it; it defines REPO, WORKSPACE, DATA_DIR and the functions below.

# Debian's ROS lives under /usr and its Python modules (catkin_pkg, rospy, rosbag) only load in
# /usr/bin/python3; a pyenv or venv python3 earlier on PATH breaks catkin and roslaunch.
export PATH="/usr/bin:/bin:/usr/sbin:/sbin:${PATH}"

REPO="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
WORKSPACE="${PDA_WORKSPACE:-${REPO}/.build/ws}"
DATA_DIR="${PDA_DATA_DIR:-$(cd "${REPO}/.." && pwd)/shared/data}"
export PDA_DATA_DIR="${DATA_DIR}"
JOBS="${PDA_JOBS:-$(nproc)}"

log() { printf '\033[1m[%s]\033[0m %s\n' "$(basename "$0")" "$*"; }

# Builds the package in a catkin workspace inside .build/. The workspace's package folder holds a
# symlink to each top-level entry of the repository (edits need no copy), but not to .build
# itself, so tools that follow links (rosrun, rospack) never loop back into the workspace.
build_package() {
  local package="${WORKSPACE}/src/pda_registration"
  mkdir -p "${WORKSPACE}/src"
  [[ -L "${package}" ]] && rm -f "${package}"  # an older layout linked the whole repository
  mkdir -p "${package}"
  find "${package}" -maxdepth 1 -type l -delete
  local entry
  for entry in "${REPO}"/* "${REPO}"/.clang-format; do
    [[ -e "${entry}" ]] && ln -sfn "${entry}" "${package}/$(basename "${entry}")"
  done
  log "building in ${WORKSPACE} (${JOBS} jobs)"
  catkin_make -C "${WORKSPACE}" -j"${JOBS}" \
    -DCMAKE_BUILD_TYPE=Release \
    -DPYTHON_EXECUTABLE=/usr/bin/python3 \
    -DPDA_DATA_DIR="${DATA_DIR}" "$@"
}

# Makes roslaunch, rosrun and the built tools visible in this shell.
source_workspace() {
  # setup.bash reads unset variables; relax nounset while it runs.
  set +u
  # shellcheck disable=SC1091
  source "${WORKSPACE}/devel/setup.bash"
  set -u
}

# wait_until SECONDS WHAT COMMAND...: runs COMMAND every 0.2 s until it succeeds; after SECONDS
# fails with "timed out after SECONDS s waiting for WHAT". Every wait in the scripts is bounded.
wait_until() {
  local limit="$1" what="$2"
  shift 2
  local end=$((SECONDS + limit))
  until "$@" >/dev/null 2>&1; do
    if ((SECONDS >= end)); then
      log "error: timed out after ${limit} s waiting for ${what}" >&2
      return 1
    fi
    sleep 0.2
  done
}

# bounded SECONDS WHAT COMMAND...: runs COMMAND under a time limit; when it fails or runs past
# SECONDS, says which step and exits the script. For the measurement scripts' long tool runs.
bounded() {
  local seconds="$1" what="$2"
  shift 2
  timeout "${seconds}" "$@" || {
    echo "[$(basename "$0")] ${what}: failed or ran past ${seconds} s" >&2
    exit 1
  }
}

# stop_process PID [SECONDS]: SIGINT (roslaunch shuts its nodes down cleanly on it), then SIGKILL
# if PID is still there after SECONDS (default 15); never waits longer.
stop_process() {
  local pid="$1" limit="${2:-15}"
  [[ -n "${pid}" ]] || return 0
  kill -INT "${pid}" 2>/dev/null || return 0
  local end=$((SECONDS + limit))
  while kill -0 "${pid}" 2>/dev/null && ((SECONDS < end)); do sleep 0.2; done
  kill -KILL "${pid}" 2>/dev/null || true
  wait "${pid}" 2>/dev/null || true
}
