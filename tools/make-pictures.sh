#!/usr/bin/env bash
# Regenerates the pictures in docs/pictures/ (README's gallery and docs/demos.md): builds the demos in
# the default configuration (build/default, as README's commands do) and runs each with --png at a
# small size, so that the committed files stay small (3 to 35 KB each). RagdollDemo also writes a short
# sequence (docs/pictures/RagdollDemo-sequence/). Run from anywhere in the clone; needs libpng-dev.
set -euo pipefail
# shellcheck source=.ci/lib.sh
source "$(dirname "${BASH_SOURCE[0]}")/../.ci/lib.sh"

caliber_ensure_packages
caliber_configure "$CALIBER_DEFAULT_BUILD_DIR" "${CALIBER_DEFAULT_CONFIG[@]}"
caliber_build "$CALIBER_DEFAULT_BUILD_DIR" caliber_demos

build="$CALIBER_ROOT/$CALIBER_DEFAULT_BUILD_DIR"
out="$CALIBER_ROOT/docs/pictures"
mkdir -p "$out"

# picture DEMO [WxH [ARGS...]]: DEMO's last frame as docs/pictures/DEMO.png (320 x 240 by default),
# checked like CI checks the demos' pictures.
picture() {
	local demo="$1"
	local size="${2:-320x240}"
	shift $(($# > 1 ? 2 : 1))
	# From the build directory: some demos also write files of their own (raytracer.png).
	(cd "$build" && "Demos/$demo/$demo" --png "$out/$demo.png" --size "$size" "$@" >/dev/null)
	"$build/Demos/Common/caliber_png_check" --size "$size" "$out/$demo.png"
}

picture LinearMathDemo
picture SimplexDemo
picture GjkConvexCastDemo
picture CollisionInterfaceDemo
picture Raytracer 192x192
picture UserCollisionAlgorithm
picture HelloWorld
picture BasicDemo
picture CcdPhysicsDemo
picture ConcaveDemo
picture ConstraintDemo 480x160
picture RagdollDemo
picture VehicleDemo
picture CharacterDemo
picture ForkLiftDemo
picture SoftDemo 320x240 Impact
picture BspDemo
picture ObjDemo
picture ConvexDecompositionDemo
picture ColladaDemo
picture BenchmarkDemo 320x240 pyramid_jolt 120

# A contact sheet's worth of RagdollDemo: the ragdolls falling and landing, every 12 frames (0.2 s).
rm -rf "$out/RagdollDemo-sequence" "$out/BasicDemo-sequence"
(cd "$build" && Demos/RagdollDemo/RagdollDemo --frames 60 --png-sequence "$out/RagdollDemo-sequence" --every 12 \
	--size 160x120 >/dev/null)
"$build/Demos/Common/caliber_png_check" --size 160x120 "$out/RagdollDemo-sequence"/*.png

# The browser pulling a box out of BasicDemo's block, when it is built and Xvfb is there (bash .ci/demos
# installs both).
if [ -x "$build/Demos/AllBulletDemos/AllBulletDemos" ] && command -v xvfb-run >/dev/null 2>&1; then
	xvfb-run -a -s "-screen 0 1280x1024x24" "$build/Demos/AllBulletDemos/AllBulletDemos" --demo BasicDemo --drag 160,125,160,30 \
		--frames 90 --size 320x240 --screenshot "$out/AllBulletDemos.png" >/dev/null
	"$build/Demos/Common/caliber_png_check" --size 320x240 "$out/AllBulletDemos.png"
fi

echo "pictures: $(find "$out" -name '*.png' | wc -l) in $out"
