#pragma once
// A frame's per-particle datasets: their names, element types and columns in
// the order a frame holds them, and their rows for a set of particles in id
// order. Written once for both writers of a frame: one process with the
// whole state, and every MPI rank with its own particles (each writing its
// rows in place in the same file). Also where a frame marks a particle as on
// its body's surface, with the outward normal.
#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "src/core/particle_store.hpp"
#include "src/core/region.hpp"
#include "src/core/solver_state.hpp"
#include "src/core/surface.hpp"

namespace mpsolid {

enum class RowType : std::uint8_t { f64, i32, i8 };
std::size_t element_bytes(RowType type);

// One per-particle dataset: `columns` values of `type` per particle.
struct RowLayout {
  const char* name;
  RowType type;
  std::size_t columns;
  std::size_t row_bytes() const { return columns * element_bytes(type); }
};

// A frame's per-particle datasets in the order a frame holds them: id, kind,
// body, position, velocity, (in space) orientation, rotation,
// angular_velocity, volumetric_strain, pressure, surface, normal.
const std::vector<RowLayout>& frame_row_layout(int dimension);

using RowValues =
    std::variant<std::vector<double>, std::vector<std::int32_t>, std::vector<std::int8_t>>;

// Where a frame marks particles as on a surface: a flag and the outward unit
// normal (z = 0 in the plane) per particle of a store, by storage index.
struct SurfaceMarks {
  std::vector<std::int8_t> flag;
  std::vector<double> nx, ny, nz;
  explicit SurfaceMarks(std::size_t n) : flag(n, 0), nx(n, 0.0), ny(n, 0.0), nz(n, 0.0) {}
};

// In the plane, a frame marks the hosts of each elastic or rigid body's
// surface nodes (src/core/surface.hpp), the normal along the host's area
// vector. `first`: the body's first storage index in the whole state.
struct FrameSurface {
  std::size_t first = 0;
  Surface surface;
};
// The surfaces of the bodies (kind and shape, in the case's order, with
// their storage ranges) a frame marks: walls and bodies whose holes touch
// have none.
std::vector<FrameSurface> frame_surfaces(const std::vector<std::pair<Kind, const Shape*>>& bodies,
                                         const std::vector<Range>& body_ranges, double l0);
// Each surface's nodes' positions, surface by surface.
using NodePositions = std::vector<std::vector<Point2>>;
// The nodes whose host `computes` takes (a host's global storage index), at
// the positions x, y of a store holding the global storage index g at
// local_of(g) (-1: not held); the others are left at zero.
NodePositions surface_nodes(const std::vector<FrameSurface>& surfaces, const double* x,
                            const double* y,
                            const std::function<std::int64_t(std::size_t)>& local_of,
                            const std::function<bool(std::size_t)>& computes);
// Given every node of every surface, the marks of the hosts `local_of` maps
// into a store of `n` particles.
SurfaceMarks plane_surface_marks(const std::vector<FrameSurface>& surfaces,
                                 const NodePositions& nodes, std::size_t n,
                                 const std::function<std::int64_t(std::size_t)>& local_of);
// In space, a particle is on the surface where it lacks one of its six
// nearest lattice neighbours; its outward normal is then minus the sum of
// its bonds' current vectors, normalised. For the particles of `marked`
// (their rows whole, their partners' positions current).
SurfaceMarks space_surface_marks(const SolverState& state, Range marked);

// The marks of a whole state (its particles all held, in global order):
// in space from the bonds, in the plane from `surfaces`' nodes.
SurfaceMarks whole_surface_marks(const SolverState& state,
                                 const std::vector<FrameSurface>& surfaces);

// The rows of `field` for `members` (storage indices of `p`, in id order).
RowValues frame_rows(const RowLayout& field, const ParticleStore& p,
                     const std::vector<std::size_t>& members, const SurfaceMarks& marks);

// What every rank writes in place into a file rank 0 laid out: a frame's
// datasets (frame_row_layout) or a checkpoint's particle arrays
// (state_arrays), each a contiguous dataset of native numbers whose row for
// id k lies at offset + k * row_bytes; or, to restore a checkpoint, reads
// from its particle arrays. A compressed frame's rows (HDF5 compresses
// whole chunks) go to rank 0 instead, chunk by chunk of ids: every rank
// sends its rows of a chunk, and rank 0's `chunk_sink` writes the chunk.
struct RowPlacement {
  enum class Content : std::int8_t { frame, checkpoint, restore, compressed_frame };
  Content content = Content::frame;
  std::string file;
  // One per dataset, in their order; a compressed frame's: the particles,
  // then the ids per chunk.
  std::vector<std::uint64_t> offsets;
  // Rank 0's, for a compressed frame (not sent): the rows of ids first,
  // first + 1, ... of each dataset (frame_row_layout's order).
  std::function<void(std::uint64_t first, const std::vector<RowValues>& rows)> chunk_sink;
  // A frame's rows (compressed or not), at the current positions.
  bool frame() const { return content == Content::frame || content == Content::compressed_frame; }
};
// What the ranks report of a placement: a checkpoint's particle arrays'
// hashes (placed_array_hash: each array's terms summed over the ranks), as
// written or as read.
struct PlacedRows {
  std::vector<std::uint64_t> array_hashes;
};
// Writes a placement's rows of every particle (over MPI ranks, each rank its
// own) and reports them.
using RowPlacer = std::function<PlacedRows(const RowPlacement&)>;

}  // namespace mpsolid
