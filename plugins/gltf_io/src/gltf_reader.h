#pragma once
// Reading a .gltf or .glb file as one triangle soup.
//
// Every triangle primitive (TRIANGLES, TRIANGLE_STRIP, TRIANGLE_FAN) of every
// mesh instance of the default scene is taken, in world coordinates; POINTS
// and LINES primitives are skipped. Attributes: POSITION, NORMAL, TEXCOORD_0
// and COLOR_0. A NORMAL or TEXCOORD_0 that some primitive lacks is dropped
// from the whole soup (a soup carries an attribute for all vertices or none);
// a missing COLOR_0 is filled with opaque white, the glTF default. Each
// primitive's material index becomes the faces' region, material names the
// region names; primitives without a material get an extra region "default".

#include <mr/core/triangle_soup.h>

#include <string>
#include <string_view>

namespace mr::plugins::gltf {

/// Reads a file's bytes; `name` is the file's path: messages name it, and
/// external buffers are looked up next to it. `require_glb`: the file is
/// read as GLB (it must carry the GLB magic). Throws InputError naming
/// `name` on anything that cannot be read.
TriangleSoup read_gltf(std::string_view bytes, const std::string& name, bool require_glb);

}  // namespace mr::plugins::gltf
