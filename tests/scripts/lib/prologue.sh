# The shared start of tests/scripts/*_test.sh (sourced): $1 = phyir binary, $2 = a scratch
# folder, emptied and made the working directory; die() fails the test with a message, and
# any failing command is reported with its line.
set -euo pipefail
phyir=$1
work=$2
rm -rf "$work"
mkdir -p "$work"
cd "$work"
die() { echo "FAIL: $*" >&2; exit 1; }
trap 'echo "FAIL: line $LINENO: $BASH_COMMAND" >&2' ERR
