// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_DEMOS_COMMON_RENDERER_H
#define CALIBER_DEMOS_COMMON_RENDERER_H
// A small software renderer for the demos' pictures: a perspective camera, a z-buffer, lit triangles
// (a key and a fill light, per-pixel), depth-tested lines and points, and supersampling for smooth
// edges. It renders a Scene into an RGB image; Png.h writes that image. Demo-side code.

#include <cstdint>
#include <string>
#include <vector>

#include "Scene.h"

namespace caliber
{
namespace demo
{
/// An 8-bit RGB image, rows top to bottom, 3 bytes per pixel.
struct Image
{
	int width = 0;
	int height = 0;
	std::vector<std::uint8_t> rgb;

	/// The pixel at (x, y) as 0xRRGGBB; x and y must be inside the image.
	std::uint32_t pixel(int x, int y) const;
};

/// A perspective camera looking from eye at target.
struct Camera
{
	btVector3 eye{0, 5, 20};
	btVector3 target{0, 0, 0};
	btVector3 up{0, 1, 0};
	/// Vertical field of view, in degrees.
	btScalar fieldOfViewDegrees = 40;

	/// Places the eye along -viewDirection from the box's centre, just far enough that the whole box is
	/// in view for an image of the given aspect ratio (width / height). A zero or non-finite direction
	/// falls back to the default view, from the front, above and to the right.
	void frame(const btVector3& aabbMin, const btVector3& aabbMax, btScalar aspect,
	           const btVector3& viewDirection = btVector3(-0.55f, -0.45f, -1));
};

/// How to render.
struct RenderOptions
{
	int width = 640;
	int height = 480;
	/// Samples per pixel along each axis (1 to 4); 2 gives smooth edges at four times the work.
	int supersampling = 2;
	/// Background colour (0..1).
	btVector3 background{0.93f, 0.94f, 0.96f};
	/// Draw lines and points over the solids instead of depth-testing them (joint frames inside bodies).
	bool linesOnTop = true;
	/// Line width in output pixels.
	int lineWidth = 1;
};

/// The largest image side render() accepts: a typo in a size should not try to allocate gigabytes.
constexpr int kMaxImageSide = 8192;

/// Renders scene as seen by camera into image. Returns false with a message in error (and leaves the
/// image empty) when the options cannot be used: a side below 1 or above kMaxImageSide, supersampling
/// outside 1..4, or a non-finite camera, or the eye on the target. Triangles crossing the camera's near plane are
/// clipped.
bool render(const Scene& scene, const Camera& camera, const RenderOptions& options, Image& image, std::string& error);

/// The camera that frames scene: its focus box if it has one, else everything in it.
Camera frameScene(const Scene& scene, const RenderOptions& options,
                  const btVector3& viewDirection = btVector3(-0.55f, -0.45f, -1));
}  // namespace demo
}  // namespace caliber

#endif
