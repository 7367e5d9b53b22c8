#include <mr/core/errors.h>
#include <mr/envelope/envelope.h>

#include "sampled_envelope.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace mr::envelope {

std::vector<std::uint8_t> Envelope::are_inside(std::span<const TriangleCorners> triangles) const {
  std::vector<std::uint8_t> inside(triangles.size(), 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, triangles.size(), 16),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t i = range.begin(); i != range.end(); ++i) {
                        const TriangleCorners& t = triangles[i];
                        inside[i] = is_inside(t[0], t[1], t[2]) ? 1 : 0;
                      }
                    });
  return inside;
}

std::vector<std::uint8_t> Envelope::are_inside(const TriangleSoup& soup) const {
  std::vector<TriangleCorners> corners(soup.triangles.size());
  for (std::size_t i = 0; i < corners.size(); ++i) {
    for (int k = 0; k < 3; ++k) {
      const Index v = soup.triangles[i][k];
      if (v >= soup.positions.size()) throw UsageError("Envelope::are_inside: vertex index out of range");
      corners[i][k] = soup.positions[v];
    }
  }
  return are_inside(corners);
}

std::unique_ptr<Envelope> make_envelope(const TriangleSoup& input, const EnvelopeOptions& options) {
  switch (options.kind) {
    case EnvelopeKind::Sampled:
      break;
  }
  return std::make_unique<SampledEnvelope>(input, options);
}

}  // namespace mr::envelope
