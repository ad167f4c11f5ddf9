# shellcheck shell=bash disable=SC2034  # the variables are used by the scripts that source this file
# Helpers shared by .ci/demos, .ci/tests and .ci/run. Sourced, never run on its own.

CALIBER_ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
CALIBER_JOBS="${CALIBER_JOBS:-2}"
# ccache (used by CMakeLists.txt when installed) keys on paths relative to the clone, so a fresh clone
# in another folder still hits the cache of an earlier run.
export CCACHE_BASEDIR="${CCACHE_BASEDIR:-$CALIBER_ROOT}"

# The default configuration: float, SIMD on, optimised, btAssert kept on, warnings are errors.
# .ci/demos and .ci/tests share it (and its build directory), so running both builds the library once.
CALIBER_DEFAULT_BUILD_DIR="build/default"
CALIBER_DEFAULT_CONFIG=(
	-DCMAKE_BUILD_TYPE=Release
	-DCALIBER_ASSERTS=ON
	-DCALIBER_WERROR=ON
	-DCALIBER_DOUBLE_PRECISION=OFF
	-DCALIBER_SIMD=ON
	-DCALIBER_SANITIZE=OFF
	-DCALIBER_TSAN=OFF
	-DCALIBER_THREADSAFE=ON
	-DCALIBER_OPENMP=OFF
	-DCALIBER_TBB=OFF
	-DBUILD_SHARED_LIBS=OFF
	-DCALIBER_BUILD_TESTS=ON
	-DCALIBER_BUILD_DEMOS=ON
	-DCALIBER_BUILD_BENCHMARKS=ON
)

# True when a Debian package is installed (not merely known to dpkg with its config files left).
caliber_package_installed() {
	dpkg-query -W -f='${Status}' "$1" 2>/dev/null | grep -q "install ok installed"
}

# caliber_ensure_packages [EXTRA...]: installs whatever the build needs and is missing, plus the
# extras asked for (each named as its Debian package: a tool, or a library package ending in -dev).
# Tools count as present when they are on PATH, libraries when their Debian package is installed.
# apt-get runs only when something is missing.
caliber_ensure_packages() {
	local missing=()
	local tool package
	local libraries=(libgtest-dev libbenchmark-dev libccd-dev libtinyxml2-dev)
	for tool in cmake g++ make pkg-config "$@"; do
		if [[ "$tool" == *-dev ]]; then
			libraries+=("$tool")
			continue
		fi
		command -v "$tool" >/dev/null 2>&1 || missing+=("$tool")
	done
	for package in "${libraries[@]}"; do
		caliber_package_installed "$package" || missing+=("$package")
	done
	if ((${#missing[@]} == 0)); then
		return 0
	fi
	# ccache is optional (the build uses it when present); it comes along when apt-get runs anyway.
	if ! command -v ccache >/dev/null 2>&1 && [[ " ${missing[*]} " != *" ccache "* ]]; then
		missing+=(ccache)
	fi

	local as_root=()
	if [ "$(id -u)" -ne 0 ]; then
		if command -v sudo >/dev/null 2>&1; then
			as_root=(sudo)
		else
			echo "error: these Debian packages are missing and installing them needs root: ${missing[*]}" >&2
			return 1
		fi
	fi
	echo "Installing missing Debian packages: ${missing[*]}"
	"${as_root[@]}" env DEBIAN_FRONTEND=noninteractive apt-get update -q
	"${as_root[@]}" env DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends "${missing[@]}"
}

# caliber_configure BUILD_DIR CMAKE_ARGS...: configures the source tree into BUILD_DIR (relative to the root).
caliber_configure() {
	local dir="$1"
	shift
	cmake -S "$CALIBER_ROOT" -B "$CALIBER_ROOT/$dir" "$@"
}

# caliber_build BUILD_DIR [TARGETS...]: builds everything, or only the given targets.
caliber_build() {
	local dir="$1"
	shift
	local targets=()
	local target
	for target in "$@"; do
		targets+=(--target "$target")
	done
	cmake --build "$CALIBER_ROOT/$dir" -j "$CALIBER_JOBS" "${targets[@]}"
}

# caliber_ctest BUILD_DIR: runs every test of a build; an empty test list is an error, not a pass.
caliber_ctest() {
	ctest --test-dir "$CALIBER_ROOT/$1" --output-on-failure --no-tests=error -j "$CALIBER_JOBS"
}

# caliber_run_demos BUILD_DIR: runs each demo listed by Demos/CMakeLists.txt, in order; any non-zero exit fails.
caliber_run_demos() {
	local list="$CALIBER_ROOT/$1/Demos/demos.txt"
	if [ ! -s "$list" ]; then
		echo "error: no demo list at $list (configure with -DCALIBER_BUILD_DEMOS=ON)" >&2
		return 1
	fi
	local demo count=0 start
	while IFS= read -r demo; do
		[ -n "$demo" ] || continue
		echo
		echo "----- $(basename "$demo") -----"
		start=$SECONDS
		# From the build directory, so that files a demo writes (raytracer.ppm) stay out of the sources.
		(cd "$CALIBER_ROOT/$1" && "$demo")
		echo "----- $(basename "$demo") finished in $((SECONDS - start))s -----"
		count=$((count + 1))
	done <"$list"
	echo
	echo "demos: $count ran, all exited 0"
}
