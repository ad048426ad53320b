#pragma once
// Self-gravity of the body by a tree code (Barnes & Hut 1986) with quadrupole and octupole
// moments of the Plummer-softened potential, for large N: `[gravity] method = "tree"`. The accuracy is set by a
// target relative force error (`[gravity] force_error`), turned into an opening angle by a
// calibration measured on this code (opening_angle_for). Units: G = M = R = 1, masses M, lengths
// R, accelerations G M/R^2, energies G M^2/R. docs/architecture.md ("Self-gravity methods").
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "model/choices.hpp"

namespace tidalcrust {

/// The opening angle theta that gives a median relative force error of about 0.8 force_error
/// (dimensionless, in (0, 0.5]) with moments up to the octupole: theta = 3.0 force_error^(2/9),
/// between 0.1 and 0.7 (0.39 at 1e-4, 0.65 at 1e-3). A calibration of this code (leaves of 32,
/// groups of 16, the octupole dropped beyond theta^(5/3)), not a bound: the median error against
/// direct summation on 30,000 random points in a sphere grows as theta^4.7 (8.3e-6 at theta
/// 0.24, 3.0e-5 at 0.31, 8.7e-5 at 0.40, 3.0e-4 at 0.51, 1.06e-3 at 0.67; 99th percentiles
/// 5.0e-5, 1.7e-4, 6.0e-4, 1.5e-3, 6.7e-3): one cell's error is its first neglected term, the
/// hexadecapole, O(theta^4) of its pull (Salmon & Warren 1994), and the errors of the many cells
/// add with partly random signs. The factor puts the median at 0.66-0.9 of the target on
/// 4,000-60,000 random points (0.72 at 30,000 and 1e-4) and the 99th percentile at 4-8 times the
/// target (with quadrupoles only the same error needed about 0.7 of the angle, three times the
/// near field). The achieved error is measured, not assumed: bench reports median, 99th
/// percentile and maximum against the direct sum.
/// `portable`: pow from portable_math (the same bits on every CPU), as the portable kernel needs.
double opening_angle_for(double force_error, bool portable = false);

/// a_i = sum_j m_j (x_j - x_i) / (|x_j - x_i|^2 + eps^2)^(3/2), approximated by an octree:
///
/// * Tree: Morton keys (21 bits per axis in the particles' bounding cube) sorted with the
///   particle index breaking ties, so the order, the nodes, their moments and everything below
///   are a pure function of positions and masses (rebuilt every call, no refit: a resumed run
///   rebuilds the same tree), by a stable radix sort, or by an insertion sort from the previous
///   call's order when that is nearly sorted (the same unique sequence, ~20x faster between
///   steps). Leaves hold <= leaf_capacity particles.
/// * Moments of each node about its centre of mass c: mass M, the second moments
///   S = sum m (x - c)(x - c)^T, the third moments O = sum m (x - c)(x - c)(x - c) and
///   b_max = max |x - c|: a leaf's from its particles, an inner node's M, c, S and O from its
///   children's (parallel-axis shifts, children in order, children before parents), b_max exactly from
///   its particles.
/// * Far field: a cell is used as a whole for a group of particles when b_max < theta d, d the
///   distance from c to the group's bounding box (Salmon & Warren 1994). Its pull is the
///   Taylor expansion of the SOFTENED kernel to third order (to second order, the octupole
///   terms dropped, when b_max < theta^(5/3) d: that truncation, O((b_max/d)^3) of the cell's
///   pull, is below theta^5, a factor theta under the hexadecapole error theta^4 of the cells
///   near the acceptance limit; it saves the octupole's ~half of the kernel's operations on
///   ~40% of the cells for +2% of median error at theta = 0.39 on the level-6 body). The
///   expansion, with r = x - c, s^2 = r^2 + eps^2,
///   a = -M r/s^3 + 3 S r/s^5 - (15/2) (r.S.r) r/s^7 + (3/2) tr(S) r/s^5
///       + (15/2) U/s^7 - (35/2) P r/s^9 - (3/2) t/s^5 + (15/2) (t.r) r/s^7
///   (U_i = O_ijk r_j r_k, P = r.U, t_k = O_iik), exact for the Plummer law up to fourth order in
///   (x_j - c)/s: no r >> eps assumption, the trace terms are what softening adds. Forces
///   evaluate it in single precision (ExpansionF) on positions relative to the group's first
///   particle (c - o rounded once from double: ~1e-7 relative per cell), widened to double every
///   64 cells; the potential (energy samples) keeps double precision.
/// * Near field: particles of opened leaves, the Plummer law pair by pair, in single precision
///   on positions relative to the group's first particle (~1e-7 relative per pair, 1,000 times
///   below the target error); the potential (energy samples) keeps double precision.
/// * Groups: runs of group_size particles consecutive in Morton order (spatially compact, all
///   vectors full) walk the tree once for all their particles; each particle then sums its
///   group's quadrupole-order cells, then its octupole-order cells, each in walk order, and,
///   apart, its group's particles in walk order (all 16 per vector of floats), then adds the
///   two in double. Every particle's sum
///   has one fixed order: the same bits for any thread count, no atomics.
/// * Walk: breadth first over child blocks (each inner node's <= 8 children side by side), the
///   acceptance test of a whole block in one vector (AVX-512) or lane by lane (portable path,
///   the same operations: the same lists in the same order). It accepts exactly the cells of
///   the classic one-node-at-a-time walk; only their order differs (by depth, not pre-order).
///   Breadth first because the next block to test is known before this one's test ends, so
///   the tests overlap; the walk took a quarter of the tree's time one node at a time.
///
/// * Build: the Morton order and the nodes on one thread (prepare()); the moments in tasks of
///   whole subtrees (at most 1/64 of the particles each, children before parents) taken
///   dynamically by any thread, with no barrier per tree level; the ~100 nodes above them and
///   the child blocks on one thread (finish_build()).
///
/// Usage: build(position), then accumulate_chunk(c) for every chunk (any order, any threads),
/// then acceleration(i) for every particle; or accelerations() for all of it.
/// The relative error per particle |a_i - b_i| / |b_i| of accelerations a against a reference b
/// (both [N*3]): its median, 99th percentile (the value below which 99% of the particles lie)
/// and maximum. Particles with b_i = 0 are skipped. Measures TreeGravity against DirectGravity.
struct ForceErrorStats {
  double median = 0, p99 = 0, max = 0;
  std::size_t particles = 0;  ///< how many particles were compared
};
ForceErrorStats relative_force_errors(const std::vector<double>& a, const std::vector<double>& reference);

class TreeGravity {
 public:
  /// mass [N] in M; softening eps in R (Body::softening); force_error in (0, 1). `kernel`: how
  /// the kernels evaluate the cells and pairs, like DirectGravity's: fast (AVX-512 estimates and
  /// fused multiply-adds where available) or portable (plain lane loops of IEEE + and *, the
  /// inverse square root by an integer guess and Newton steps, and the opening angle from
  /// portable_math: the same bits in every x86-64 build; bench reports its cost). Both walk the same lists in the same order.
  TreeGravity(const std::vector<double>& mass, double softening, double force_error,
              GravityKernel kernel = GravityKernel::fast);

  /// Builds the tree for positions [N*3] (R): prepare(), every moment_task() (in parallel, one
  /// dynamic loop: no barrier per tree level), finish_build().
  void build(const double* position);
  // build() in pieces, so a caller can run the moment tasks among its own work (ForceField does,
  // with the spring and hinge chunks): prepare(position) on one thread (Morton order, nodes,
  // groups), then moment_task(t) for every t < moment_task_count() (any order, any threads),
  // then finish_build() on one thread. Each node's moments are computed by one task from its
  // children's in a fixed order: the same bits however the tasks are scheduled.
  void prepare(const double* position);
  std::size_t moment_task_count() const { return task_roots_.size(); }
  /// Moments and expansions of the nodes of one subtree, children before parents, and the
  /// bounding boxes of the groups that start in it.
  void moment_task(std::size_t task);
  /// The nodes above the subtrees (few, near the root) and the walk's child blocks.
  void finish_build();
  /// Number of independent units of work of accumulate_chunk after build().
  std::size_t chunk_count() const { return (groups_.size() + groups_per_chunk - 1) / groups_per_chunk; }
  /// Accelerations of the particles of one chunk of groups (into the internal buffer).
  void accumulate_chunk(std::size_t chunk);
  /// The particles whose accelerations accumulate_chunk(chunk) writes: Morton positions
  /// [chunk_begin(chunk), chunk_end(chunk)), original indices original_index(k) (after build).
  std::size_t chunk_begin(std::size_t chunk) const { return groups_[chunk * groups_per_chunk].begin; }
  std::size_t chunk_end(std::size_t chunk) const {
    return groups_[std::min(groups_.size(), (chunk + 1) * groups_per_chunk) - 1].end;
  }
  std::size_t original_index(std::size_t k) const { return order_[k]; }
  /// a[3] = acceleration (G M/R^2) of particle i (original index) after every chunk ran.
  void acceleration(std::size_t i, double* a) const {
    for (std::size_t k = 0; k < 3; ++k) a[k] = acceleration_[3 * i + k];
  }

  /// Writes accelerations [N*3] (G M/R^2) for positions [N*3] (R); `parallel` false keeps the
  /// work on the calling thread (same result).
  void accelerations(const double* position, double* acceleration, bool parallel = true);

  /// Potential energy of the self-gravity, (1/2) sum_i m_i phi_i with phi_i from the same tree
  /// and expansion as the forces (G M^2/R), for positions [N*3] (R); the self-pair is excluded
  /// like in self_gravity_energy. Deterministic (per-particle sums in a fixed order, added in
  /// index order).
  double potential_energy(const double* position);

  /// Mass (M) that the interaction list of group `group` (0 .. group_count() - 1) covers after
  /// build(): its accepted cells' masses plus its near-field particles' masses. Equal to the
  /// total mass (to rounding) when the walk takes every particle exactly once (a check).
  double covered_mass(std::size_t group) const;
  std::size_t group_count() const { return groups_.size(); }
  /// Whether the last build() sorted by an insertion sort from the previous call's order (true)
  /// or by the radix sort from the index order (false): the same tree either way.
  bool sorted_from_previous_order() const { return sorted_from_previous_order_; }

  GravityKernel kernel() const { return kernel_; }
  double opening_angle() const { return theta_; }
  /// theta_q = theta^(5/3): a cell with b_max < theta_q d is summed to quadrupole order.
  double quadrupole_angle() const { return theta_quadrupole_; }
  std::size_t particle_count() const { return count_; }
  std::size_t node_count() const { return nodes_.size(); }

  static constexpr std::size_t leaf_capacity = 32;
  static constexpr std::size_t group_size = 16;
  static constexpr std::size_t groups_per_chunk = 16;

 private:
  struct Node {  ///< what the walk reads
    std::uint32_t begin, end;  ///< particle range in Morton order
    std::uint32_t next;        ///< the node after this one's subtree (pre-order)
    bool leaf;
    double com[3];     ///< centre of mass c
    double bmax2;      ///< b_max^2
  };
  /// A node's moments as the far-field kernel uses them, scaled by the constants of the
  /// expansion: 32 doubles, four cache lines, read with broadcasts.
  struct alignas(64) Expansion {
    double com[3];
    double neg_mass;   ///< -M
    double t15;        ///< (3/2) tr S
    double s3[6];      ///< 3 S: xx, xy, xz, yy, yz, zz (S = sum m (x - c)(x - c)^T)
    double mt15[3];    ///< -(3/2) t, t_k = O_iik (O_ijk = sum m d_i d_j d_k, d = x - c)
    /// (15/2) O_ijk r_j r_k as coefficients of r_x^2, r_y^2, r_z^2, r_x r_y, r_x r_z, r_y r_z
    /// (the mixed ones doubled), for i = x, y, z
    double u[18];
  };
  /// The same expansion in single precision for the far field of accumulate_chunk (the com
  /// stays in Node, in double: the kernel takes it relative to the group's first particle).
  /// 29 floats used, two cache lines.
  struct alignas(64) ExpansionF {
    float neg_mass, t15, s3[6], mt15[3], u[18];
  };
  /// A node's raw moments about its own centre of mass (the build's bottom-up pass): mass,
  /// S (xx, xy, xz, yy, yz, zz) and O (xxx, xxy, xxz, xyy, xyz, xzz, yyy, yyz, yzz, zzz).
  struct Moments {
    double mass, s[6], o[10];
  };
  struct Group {
    std::uint32_t begin, end;  ///< particle range in Morton order
    double lo[3], hi[3];       ///< bounding box of its particles
  };
  /// Appends the node of [begin, end) at depth `level` and its subtree; returns its index.
  std::uint32_t build_node(std::uint32_t begin, std::uint32_t end, int level);
  /// Moments of a leaf from its particles, of an inner node from its children's moments
  /// (children first: the build runs the nodes in reverse pre-order).
  void compute_moments(std::size_t node);
  void combine_moments(std::size_t node);
  /// Expansion and ExpansionF of a node from moments_.
  void finish_expansion(std::size_t node);
  /// What a group interacts with: the accepted cells (node indices; to octupole order
  /// cells[0, cell_count), to quadrupole order quadrupole_cells[0, quadrupole_count)) and the
  /// particle ranges [begin, end) of the opened leaves, all in walk order.
  struct InteractionList {
    explicit InteractionList(std::size_t nodes)
        : cells(new std::uint32_t[nodes + 8]),
          quadrupole_cells(new std::uint32_t[nodes + 8]),
          queue(new std::uint32_t[nodes + 8]) {}
    std::unique_ptr<std::uint32_t[]> cells;  ///< room for every node (a list never repeats one) + 8 of slack
    /// The accepted cells far enough that their octupole is dropped (b_max < theta_q d), as long.
    std::unique_ptr<std::uint32_t[]> quadrupole_cells;
    std::unique_ptr<std::uint32_t[]> queue;  ///< the walk's queue of child blocks, as long
    std::size_t cell_count = 0, quadrupole_count = 0;
    std::vector<std::uint32_t> ranges;
  };
  /// Interaction list of group g: a breadth-first walk over the child blocks (child_blocks()),
  /// testing the up to 8 children of an opened node at once.
  void interaction_list(const Group& g, InteractionList& list) const;
  /// The walk's copy of the tree: each inner node's children side by side in one block of 8
  /// slots (centres and b_max^2 as separate arrays for vector loads), in pre-order of the nodes.
  void child_blocks();
  /// phi (potential per unit mass) of the particles of group g, into potential_ (Morton order).
  void group_potential(const Group& g, InteractionList& list);
  /// accumulate_chunk and group_potential with the vectors of one kernel (tree_gravity.cpp).
  template <class Math>
  void accumulate_chunk_with(std::size_t chunk);
  template <class Math>
  void group_potential_with(const Group& g, InteractionList& list);

  GravityKernel kernel_;
  std::size_t count_;
  double eps2_;
  double theta_;
  double theta_quadrupole_;
  std::vector<double> mass_;
  std::vector<std::uint64_t> key_;
  struct Keyed {
    std::uint64_t key;
    std::uint32_t index;
  };
  std::vector<Keyed> keyed_, sorted_;  ///< [N] Morton keys being sorted (kept to save allocations)
  std::vector<std::uint32_t> order_;  ///< order_[k] = original index of the k-th particle in Morton order
  bool have_order_ = false;           ///< order_ holds a pass's order (the next sort starts from it)
  bool sorted_from_previous_order_ = false;
  std::vector<double> x_, y_, z_, m_; ///< positions and masses in Morton order
  std::vector<Node> nodes_;
  std::vector<Expansion> expansion_;  ///< [nodes_.size()]
  std::vector<ExpansionF> expansion_f_;  ///< [nodes_.size()]
  std::vector<Moments> moments_;      ///< [nodes_.size()]
  /// Roots of the subtrees of the moment tasks, in pre-order (their particle ranges partition
  /// the particles), and the nodes above them (pre-order; finish_build() runs them backwards).
  std::vector<std::uint32_t> task_roots_, top_nodes_;
  std::vector<std::uint32_t> block_of_;  ///< [nodes] an inner node's child block (leaves: unused)
  /// Child blocks [8 * blocks]: slot 8 b + l is the l-th child of the inner node of block b.
  std::vector<double> walk_x_, walk_y_, walk_z_, walk_bmax2_;
  std::vector<std::uint32_t> walk_node_;   ///< the child's node index
  std::vector<std::uint32_t> walk_block_;  ///< an inner child's own block
  std::vector<std::uint8_t> block_valid_;  ///< [blocks] bit l: slot l holds a child
  std::vector<std::uint8_t> block_leaf_;   ///< [blocks] bit l: that child is a leaf
  std::vector<Group> groups_;
  std::vector<double> acceleration_;  ///< [N*3] by original index
  std::vector<double> potential_;     ///< [N] in Morton order (potential_energy)
};

}  // namespace tidalcrust
