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
	# libpng-dev (the demos' pictures) and libtinyxml2-dev (the COLLADA converter in Extras/) are optional
	# for the build; CI installs them so that they are tested.
	local libraries=(libgtest-dev libbenchmark-dev libccd-dev libpng-dev libtinyxml2-dev)
	for tool in cmake g++ make pkg-config "$@"; do
		if [[ "$tool" == *-dev ]]; then
			libraries+=("$tool")
			continue
		fi
		# A package whose name is not its program (xvfb, libgl1-mesa-dri) counts as present when installed.
		command -v "$tool" >/dev/null 2>&1 || caliber_package_installed "$tool" || missing+=("$tool")
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
# When the build has libpng (it built caliber_png_check), each demo also writes a picture of its last
# frame with --png to BUILD_DIR/pictures/<demo>.png, and the checker then makes sure every picture
# decodes, has the size the demo reported ("picture: PATH (W x H)") and shows a scene (not a blank or
# one-colour frame).
# BenchmarkDemo's scenes in Bullet 2.89's multithreaded world at 1 and 2 threads: every scene must be
# sane and print the same state hash (docs/threading.md).
caliber_check_threaded_benchmark() {
	local demo="$CALIBER_ROOT/$1/Demos/BenchmarkDemo/BenchmarkDemo"
	local one two
	one=$("$demo" all 30 --threads 1 | grep -o '^[a-z_0-9][a-z_0-9]* \|hash [0-9a-f]*') || return 1
	two=$("$demo" all 30 --threads 2 | grep -o '^[a-z_0-9][a-z_0-9]* \|hash [0-9a-f]*') || return 1
	echo "$two" | paste - -
	if [ "$one" != "$two" ] || [ -z "$one" ]; then
		echo "BenchmarkDemo --threads: the state hashes differ between 1 and 2 threads" >&2
		return 1
	fi
	echo "BenchmarkDemo --threads: the same state hashes at 1 and 2 threads: ok"
}

caliber_run_demos() {
	local list="$CALIBER_ROOT/$1/Demos/demos.txt"
	if [ ! -s "$list" ]; then
		echo "error: no demo list at $list (configure with -DCALIBER_BUILD_DEMOS=ON)" >&2
		return 1
	fi
	local checker="$CALIBER_ROOT/$1/Demos/Common/caliber_png_check"
	local pictures="$CALIBER_ROOT/$1/pictures"
	local with_pictures=0
	if [ -x "$checker" ]; then
		with_pictures=1
		rm -rf "$pictures"
		mkdir -p "$pictures"
	fi
	local demo name count=0 start
	local picture_args=()
	while IFS= read -r demo; do
		[ -n "$demo" ] || continue
		name="$(basename "$demo")"
		picture_args=()
		if ((with_pictures)); then
			picture_args=(--png "$pictures/$name.png")
		fi
		echo
		echo "----- $name -----"
		start=$SECONDS
		# From the build directory, so that files a demo writes (raytracer.png) stay out of the sources.
		# The output is kept for the picture check (the callers set pipefail: a failing demo still fails).
		(cd "$CALIBER_ROOT/$1" && "$demo" "${picture_args[@]}") | tee "$CALIBER_ROOT/$1/Demos/$name.out"
		echo "----- $name finished in $((SECONDS - start))s -----"
		count=$((count + 1))
	done <"$list"
	echo
	echo "demos: $count ran, all exited 0"
	if ((with_pictures)); then
		echo
		echo "----- pictures -----"
		local size failed=0
		while IFS= read -r demo; do
			[ -n "$demo" ] || continue
			name="$(basename "$demo")"
			size="$(sed -n 's/^picture: .* (\([0-9]*\) x \([0-9]*\))$/\1x\2/p' "$CALIBER_ROOT/$1/Demos/$name.out")"
			if [ -z "$size" ]; then
				echo "$name: FAILED: it did not report a picture for --png"
				failed=1
				continue
			fi
			"$checker" --size "$size" "$pictures/$name.png" || failed=1
		done <"$list"
		if ((failed)); then
			echo "error: some demo pictures are missing, the wrong size or blank (see above)" >&2
			return 1
		fi
		echo "pictures: $count checked in $pictures"
	else
		echo "pictures: not checked (this build has no libpng; install libpng-dev)"
	fi
}

# The demo browser's packages: GLFW and OpenGL to build it, Xvfb and Mesa's software OpenGL to run it
# without a screen. .ci/demos installs them; the browser is skipped in builds without them.
CALIBER_BROWSER_PACKAGES=(libglfw3-dev libgl-dev xvfb xauth libgl1-mesa-dri)

# caliber_check_browser BUILD_DIR: runs AllBulletDemos under Xvfb (Mesa's software OpenGL): every demo
# of its list for a few steps with a screenshot, each checked like the demos' pictures, and a scripted
# mouse drag that must pick a body of BasicDemo and pull it up.
caliber_check_browser() {
	local browser="$CALIBER_ROOT/$1/Demos/AllBulletDemos/AllBulletDemos"
	local checker="$CALIBER_ROOT/$1/Demos/Common/caliber_png_check"
	if [ ! -x "$browser" ]; then
		echo "browser: not built (it needs libglfw3-dev and libgl-dev)"
		return 0
	fi
	if ! command -v xvfb-run >/dev/null 2>&1 || [ ! -x "$checker" ]; then
		echo "error: the browser is built but xvfb-run or caliber_png_check is missing" >&2
		return 1
	fi
	local shots="$CALIBER_ROOT/$1/pictures/browser"
	rm -rf "$shots"
	mkdir -p "$shots"
	local xvfb=(xvfb-run -a -s "-screen 0 1280x1024x24")
	local demo file
	echo
	echo "----- AllBulletDemos under Xvfb -----"
	while IFS= read -r demo; do
		file="$shots/$(echo "$demo" | tr '/' '_').png"
		# Without the on-screen text (H), so that what is checked is the scene. An Extras demo whose
		# library this build lacks (ColladaDemo without tinyxml2) says it is skipped: nothing to check.
		"${xvfb[@]}" "$browser" --demo "$demo" --frames 10 --size 640x480 --keys h@0 --screenshot "$file" \
			2>"$shots/stderr.txt"
		if grep -q " is skipped: " "$shots/stderr.txt"; then
			cat "$shots/stderr.txt"
			continue
		fi
		cat "$shots/stderr.txt" >&2
		# 0.5%: ConstraintDemo's small joints hang in a 27 m row over no ground (0.7% of the frame);
		# a blank or one-colour frame still fails.
		"$checker" --size 640x480 --min-scene 0.5 "$file"
	done < <("$browser" --list)
	local out
	out="$("${xvfb[@]}" "$browser" --demo BasicDemo --frames 90 --size 1024x768 --drag 512,400,512,100 \
		--screenshot "$shots/drag.png")"
	echo "$out"
	"$checker" --size 1024x768 "$shots/drag.png"
	# The box under the cursor must have followed it up by more than a metre.
	echo "$out" | awk '/^drag: picked/ { if ($(NF - 1) + 0 > 1) ok = 1 } END { exit ok ? 0 : 1 }' || {
		echo "error: the scripted drag did not pull a body up" >&2
		return 1
	}
	# Driving keys: with the up arrow held for 2 s the car, the character and the fork lift must move
	# off (over 3 m: each goes 2 to 3 m/s once under way).
	for demo in VehicleDemo CharacterDemo ForkLiftDemo; do
		out="$("${xvfb[@]}" "$browser" --demo "$demo" --frames 120 --size 320x240 --hold up)"
		echo "$out"
		echo "$out" | awk '/^hold: the driver moved/ { if ($NF == "m" && $(NF - 1) + 0 > 3) ok = 1 } END { exit ok ? 0 : 1 }' || {
			echo "error: the up arrow did not drive $demo" >&2
			return 1
		}
	done
	echo "browser: every demo drawn, a body picked and dragged, the driven demos driven"
	caliber_check_browser_input "$1"
}

# caliber_check_browser_input BUILD_DIR: the browser's mouse and keys, scripted (--orbit, --pan, --wheel,
# --keys, --drag) under Xvfb, each judged from what the browser prints (its camera, and a hash of the
# bodies' exact positions) and from its screenshots (caliber_png_check --box, --near, --diff). A few
# seconds in all: each run is a few steps of a small scene at 320 x 240.
caliber_check_browser_input() {
	local browser="$CALIBER_ROOT/$1/Demos/AllBulletDemos/AllBulletDemos"
	local checker="$CALIBER_ROOT/$1/Demos/Common/caliber_png_check"
	[ -x "$browser" ] || return 0
	local shots="$CALIBER_ROOT/$1/pictures/browser-input"
	rm -rf "$shots"
	mkdir -p "$shots"
	echo
	echo "----- AllBulletDemos: mouse and keys -----"
	# browse NAME ARGS...: one scripted run, 320 x 240, its report in $shots/NAME.out and its
	# screenshot in $shots/NAME.png.
	browse() {
		local name="$1"
		shift
		xvfb-run -a -s "-screen 0 1280x1024x24" "$browser" --size 320x240 --screenshot "$shots/$name.png" "$@" \
			>"$shots/$name.out"
	}
	# field NAME LINE N: the Nth field of the report line starting with LINE.
	field() { awk -v line="$2" -v n="$3" '$1 == line { gsub(/[(),]/, ""); print $n; exit }' "$shots/$1.out"; }
	box() { "$checker" --size 320x240 --box "$shots/$1.png" | awk '$2 == "box" { print $3, $4, $5, $6 }'; }
	near() { "$checker" --size 320x240 --near "$2" "$shots/$1.png" | awk '$2 == "near" { print $4 }'; }
	differ() { "$checker" --diff "$shots/$1.png" "$shots/$2.png" | awk '{ print $4 }'; }
	fail() {
		echo "error: browser input: $*" >&2
		return 1
	}
	# Camera: SimplexDemo's replay has no ground, so the box around its pixels is the scene's. The
	# on-screen text is hidden (H) so that it does not count.
	browse view --demo SimplexDemo --frames 1 --keys h@0
	browse zoom --demo SimplexDemo --frames 1 --keys h@0 --wheel 3
	browse pan --demo SimplexDemo --frames 1 --keys h@0 --pan 60,0
	browse orbit --demo SimplexDemo --frames 1 --keys h@0 --orbit 200,0
	# "camera: target (x, y, z), yaw Y, pitch P, distance D": fields 3-5 the target, 7 yaw, 11 distance;
	# "end: N objects, M dynamic, mean centre (x, y, z), hash H": field 2 the objects, 12 the hash.
	local d0 d1 w0 w1
	d0="$(field view camera: 11)"
	d1="$(field zoom camera: 11)"
	read -r x0 _ x1 _ <<<"$(box view)"
	w0=$((x1 - x0))
	read -r x0 _ x1 _ <<<"$(box zoom)"
	w1=$((x1 - x0))
	echo "zoom: 3 wheel steps: distance $d0 -> $d1 m, scene $w0 -> $w1 pixels wide"
	# Each wheel step brings the eye 10% closer: 0.9^3 = 0.729. The scene then looks 1/0.729 = 1.37
	# times as wide (less where it runs off the 320-pixel window): more than 1.15 times.
	awk -v a="$d0" -v b="$d1" -v w0="$w0" -v w1="$w1" \
		'BEGIN { r = b / a; exit !(r > 0.728 && r < 0.730 && w1 > 1.15 * w0) }' || fail "zoom"
	local left0 left1
	left0="$(box view | awk '{ print $1 }')"
	left1="$(box pan | awk '{ print $1 }')"
	echo "pan: a 60-pixel right-drag: target x $(field view camera: 3) -> $(field pan camera: 3), scene's left edge $left0 -> $left1"
	# The scene follows the mouse: its left edge moves right, by 60 * 0.0015 * 240 / (2 tan 20 deg) = 30
	# pixels at the target's depth (nearer and farther parts move a little more or less): over 15.
	awk -v a="$left0" -v b="$left1" 'BEGIN { exit !(b - a > 15 && b - a < 60) }' || fail "pan"
	local yaw0 yaw1 changed
	yaw0="$(field view camera: 7)"
	yaw1="$(field orbit camera: 7)"
	changed="$(differ view orbit)"
	echo "orbit: a 200-pixel left-drag over empty space: yaw $yaw0 -> $yaw1, $changed pixels differ"
	# 0.005 rad a pixel: the yaw turns by -1 rad; the picture changes (the scene is 1.8% of it).
	awk -v a="$yaw0" -v b="$yaw1" -v n="$changed" 'BEGIN { d = b - a; exit !(d > -1.001 && d < -0.999 && n > 1000) }' \
		|| fail "orbit"

	# Keys on BasicDemo's block. "start:" and "end:" report the bodies: equal hashes, the same state.
	browse step1 --demo BasicDemo --frames 1 --keys h@0
	browse paused --demo BasicDemo --frames 30 --keys h@0,space@0
	browse single --demo BasicDemo --frames 30 --keys h@0,space@0,s@10
	browse reset --demo BasicDemo --frames 30 --keys h@0,r@29
	browse shoot --demo BasicDemo --frames 30 --keys h@0,b@0
	browse next --demo BasicDemo --frames 1 --keys h@0,n@0
	local start end
	start="$(field paused start: 12)"
	end="$(field paused end: 12)"
	echo "pause (space): 30 steps paused: hash $start -> $end"
	[ -n "$start" ] && [ "$start" = "$end" ] || fail "the paused world moved"
	echo "single step (S while paused): hash $(field single end: 12), one step from the start: $(field step1 end: 12)"
	[ "$(field single end: 12)" = "$(field step1 end: 12)" ] || fail "S did not make exactly one step"
	echo "reset (R) after 29 steps, then one step: hash $(field reset end: 12), one step from the start: $(field step1 end: 12)"
	[ "$(field reset end: 12)" = "$(field step1 end: 12)" ] || fail "R did not bring back the start"
	echo "shoot (B): $(field shoot start: 2) -> $(field shoot end: 2) objects"
	[ "$(field shoot end: 2)" = "$(($(field shoot start: 2) + 1))" ] || fail "B did not add a box"
	grep -q "^AllBulletDemos: RagdollDemo," "$shots/next.out" || fail "N did not switch to the next demo"
	echo "next (N): BasicDemo -> RagdollDemo"

	# Debug-draw toggles against step1's picture: AABBs (A) add red lines (btIDebugDraw's default AABB
	# colour), contact points (C, after 30 steps at rest) yellow ones, wireframe (W) redraws the solids.
	browse aabb --demo BasicDemo --frames 1 --keys h@0,a@0
	browse rest --demo BasicDemo --frames 30 --keys h@0
	browse contacts --demo BasicDemo --frames 30 --keys h@0,c@0
	browse wireframe --demo BasicDemo --frames 1 --keys h@0,w@0
	local red0 red1 yellow0 yellow1 wire
	red0="$(near step1 255,0,0)"
	red1="$(near aabb 255,0,0)"
	yellow0="$(near rest 255,255,0)"
	yellow1="$(near contacts 255,255,0)"
	wire="$(differ step1 wireframe)"
	echo "A: red pixels $red0 -> $red1; C: yellow pixels $yellow0 -> $yellow1; W: $wire pixels differ"
	# 125 boxes' AABBs and 4 contacts under each bottom box: thousands of pixels, from none.
	[ "$red0" -lt 100 ] && [ "$red1" -gt 2000 ] || fail "A did not draw the AABBs"
	[ "$yellow0" -lt 100 ] && [ "$yellow1" -gt 500 ] || fail "C did not draw the contact points"
	[ "$wire" -gt 5000 ] || fail "W did not change the drawing"

	# Soft bodies are picked too: a left-drag on the cloth holds its nearest node, which follows the
	# cursor up (the cloth hangs from two corners): the node moves over 2 m and ends within 0.5 m of the
	# cursor's point.
	browse cloth --demo SoftDemo/Cloth --frames 60 --drag 160,140,160,40
	grep "^drag:" "$shots/cloth.out"
	awk '/^drag: picked node/ { if ($(NF - 14) + 0 > 2 && $(NF - 4) + 0 < 0.5) ok = 1 } END { exit !ok }' \
		"$shots/cloth.out" || fail "the drag did not pull the cloth's node"

	# R during a drag takes the picked body away with the demo: the report says so and exits 1, it does
	# not read the body that is gone.
	if browse gone --demo BasicDemo --frames 10 --drag 160,125,160,30 --keys h@0,r@5; then
		fail "a drag across a reset was reported as a success"
	fi
	grep -q "^drag: the demo was loaded again during the drag" "$shots/gone.out" || fail "a drag across a reset"
	echo "R during a drag: the pick is dropped and reported"

	# Bad input is refused with exit 2 before a window opens.
	local bad
	for bad in "--keys x@0" "--keys s" "--keys s@20 --frames 10" "--wheel many" "--orbit 1" "--pan 1,2,3"; do
		# shellcheck disable=SC2086
		if "$browser" --demo BasicDemo $bad >/dev/null 2>&1; then
			fail "'$bad' was accepted"
		elif [ $? -ne 2 ]; then
			fail "'$bad' did not exit 2"
		fi
	done
	echo "browser input: camera orbit, pan and zoom, pause, step, reset, next, shoot, the overlays and a soft-body drag all checked"
}
