# Shared by the scripts that measure Strata on the repository's cases (issue_cases.sh,
# sweep_cases.sh, settings_sweep.sh, pipeline_times.sh): source it, then call
#   measure_setup [BUILD_DIR] [WORK_DIR]     (defaults: build, a temporary directory)
# which sets root (the repository), build, work (created) and strata (the CLI in build).

measure_setup() {
  root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
  build=$(cd "${1:-$root/build}" && pwd)
  work=${2:-$(mktemp -d)}
  mkdir -p "$work"
  strata=$build/app/strata
}
