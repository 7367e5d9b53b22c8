#pragma once
// Draco's decoder cannot be stopped from outside, and a file of a few hundred
// bytes can keep it busy for seconds: the portable texture-coordinate
// prediction (MeshPredictionSchemeTexCoordsPortableDecoder, libdraco 1.5.5
// and upstream) reads its number of orientations as an unbounded int32 and
// decodes that many bits, which its rANS decoder goes on returning past the
// data. A 10 KB file asking for 2^31 - 1 of them decodes successfully after
// 9 s and 300 MB. The field lies behind the connectivity and the earlier
// attributes, so it cannot be checked without decoding the stream.
//
// So a mesh is first decoded in a child process under a CPU-time limit
// proportional to its size; only a trial that ends is followed by the real
// decode in this process. It costs a fork and a second decode (Draco decodes
// about 7 MB of mesh a second here, a small share of any run that reads it)
// and also turns a crash inside Draco into a message.

#include <cstddef>
#include <string>
#include <string_view>

namespace mr::plugins::detail {

/// CPU time a trial decode of `bytes` may take: a second, plus two a megabyte
/// (about 14 times what a valid mesh needs in a Release build).
struct DracoTrialLimits {
  double base_seconds = 1.0;
  double seconds_per_megabyte = 2.0;
  double seconds_for(std::size_t bytes) const {
    return base_seconds + seconds_per_megabyte * double(bytes) / 1e6;
  }
};

/// Decodes `bytes` as a Draco mesh in a child process. Throws InputError
/// naming `source` if the child runs past its limit or dies of a signal;
/// returns when it ended by itself, whether or not the mesh was valid (the
/// decode that follows reports an invalid one with Draco's own message).
void trial_decode_draco(std::string_view bytes, const std::string& source,
                        const DracoTrialLimits& limits = {});

}  // namespace mr::plugins::detail
