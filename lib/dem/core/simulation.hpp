#pragma once
// The explicit DEM cycle of Kiyama & Fujimura (docs/model.md §1, docs/references.md §1.4), for disks and
// pseudo-rectangle elements: contact forces from the increments of the step (K5–K15, M3–M12),
// velocities (K17), next increments (K18 or K19), positions.
#include <array>
#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "dem/contact/contact_slots.hpp"
#include "dem/core/contact_index.hpp"
#include "dem/core/corner_contacts.hpp"
#include "dem/core/model.hpp"
#include "dem/core/neighbour_search.hpp"
#include "dem/core/polygon_slots.hpp"
#include "dem/core/spatial_order.hpp"
#include "dem/core/stability.hpp"
#include "dem/core/thread_governor.hpp"
#include "dem/core/thread_shares.hpp"
#include "dem/core/step_timings.hpp"
#include "dem/core/worker_threads.hpp"

// (not under ThreadSanitizer: the clones' resolvers run while the program is loaded, before TSan starts)
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && !defined(__SANITIZE_THREAD__)
#define DEM2D_CLONES_AVX2 [[gnu::target_clones("avx2", "default")]]
#else
#define DEM2D_CLONES_AVX2
#endif

namespace dem {

struct Energies {
  double kinetic = 0.0;    // ½ m v² + ½ I ω² with the velocities of the last step [J]
  double potential = 0.0;  // −Σ m g·x [J]
  double elastic = 0.0;    // energy stored in the contact springs [J]
  double total() const { return kinetic + potential + elastic; }
};

/// One contact for outputs: who, where, which forces.
struct ContactView {
  std::uint32_t i, j;
  bool wall;
  double nx, ny;   // normal from i towards j
  double fn, fs;   // normal (compression positive) and shear force [N]
  int links;       // linked segments (1 for a linear contact)
  double mr = 0.0; // rolling moment on i (R6) [N·m]; on j the opposite; 0 without rolling
  bool at_point = false;     // a polygon's contact point (P5–P7): where it acts
  double px = 0.0, py = 0.0;  // [m]
};

/// The dashpots of a linear contact between masses m_i and m_j (m_j <= 0: a wall): explicit, or from
/// the damping ratio (K20, K25) with the law's mass basis.
struct Dashpots {
  double eta_n = 0.0, eta_s = 0.0;  // [N·s/m]
};
Dashpots linear_dashpots(const PairLaw& law, double mass_i, double mass_j);

/// The constants of a face contact between radii r_i and r_j (0: a wall) with reduced mass m_eff (M6,
/// M7.3, M7.4, M19).
FaceConstants face_constants(const PairLaw& law, double r_i, double r_j, double m_eff, double thickness);

/// The bookkeeping of a slot list merged at a rebuild on several threads (rebuild.cpp, merge_on).
struct MergePlan {
  std::vector<std::uint32_t> dest, place;  // per old slot, per candidate: its place within its range, or none
  std::vector<std::size_t> at;             // where each thread's range starts in the merged list
};
/// A whole linear pair slot (the columns of LinearPairSlots at one index).
struct FullPairSlot {
  SlotPair pair;
  std::uint8_t touching = 0;
  std::int32_t law = -1;
  LinearContactState state;
  RollingState rolling;  // if the slots have the rolling column
};

class Simulation {
 public:
  explicit Simulation(Model model);

  /// Advances one step. (Blow-ups are detected by the caller: run.cpp checks energy and NaN.)
  void step();
  /// The same step stated as Kiyama's cycle on one thread, contact by contact and element by element, without
  /// the optimised machinery (reference_step.cpp): the oracle that step() on any number of threads must match
  /// bit for bit (tests/lib/core/reference_step_tests.cpp). It makes no blow-up test (overstep() finds none).
  void reference_step();

  const Model& model() const { return m_; }
  Model& model() {  // whoever may change the model: the next step makes its own rebuild test
    tested_step_ = -1;
    travel_ = kTravelUnknown;
    return m_;
  }
  double time() const { return time_; }
  std::int64_t steps() const { return step_; }
  double dt() const { return m_.numerics.dt; }

  /// Summed in fixed chunks (energies() in observables.cpp): the same bits on any number of threads.
  Energies energies() const;
  static constexpr std::size_t kEnergyChunk = 4096;
  /// Whether the steps keep each linear element–element contact's forces and normal (its resultant) for
  /// the readers below: on unless switched off. Off, a step skips 32 bytes per contact that nothing in the
  /// next step reads (bench/journal.md, "Contact forces kept only for the steps that report them"); the
  /// readers then refuse (std::logic_error) until a step keeps them again. Wall contacts keep theirs always.
  void keep_contact_forces(bool on) { keep_forces_ = on; }
  bool contact_forces_current() const { return forces_step_ == step_; }

  std::vector<ContactView> contacts() const;
  std::size_t contact_count() const;  // touching pairs and wall contacts
  /// Sum of |f_n n + f_s t| over the contacts that carry force, and their number (no allocation).
  std::pair<double, std::size_t> contact_force_sum() const;
  /// Normal and shear force of the contact between element i and element j (or wall j); zero if none.
  ContactView contact(std::uint32_t i, std::uint32_t j, bool wall) const;
  /// The force the elements exert on wall w through the contacts whose contact point (the wall's point
  /// closest to the element's centre) lies in the band s0 <= s < s1 along the wall (s: distance from the
  /// wall's first end point a along a→b, in [0, |ab|]; 0 for a point wall): the normal part (compression
  /// positive) and the part of the force on the wall along a→b [N], and the largest normal force of a
  /// single contact in the band (0 if none: a silo's per-contact overpressure). No allocation.
  struct BandForce {
    double normal = 0.0, tangential = 0.0, max_normal = 0.0;
    std::size_t contacts = 0;
  };
  BandForce wall_band_force(std::uint32_t w, double s0, double s1) const;
  /// Every contact of wall w, one by one, as wall_band_force sums them (wall_contact_forces.cpp): where
  /// it touches (s along a→b and the point), the normal part and the part of the force on the wall along
  /// a→b [N]; in the order of the contact slots.
  struct WallContactForce {
    double s = 0.0;
    Vec2 point{};
    double normal = 0.0, tangential = 0.0;
  };
  std::vector<WallContactForce> wall_contact_forces(std::uint32_t w) const;

  /// The segments of the touching face contact between elements i and j (or element i and wall j), as
  /// array indices (face_segments.cpp): their number N and each one's state in the order of ξ_i (M13),
  /// along t = n turned by +90°, n from i towards j; n = 0 if there is no such face contact.
  struct FaceSegments {
    int n = 0;
    std::array<SegmentState, kMaxSegments> seg{};
  };
  FaceSegments face_segments(std::uint32_t i, std::uint32_t j, bool wall) const;

  /// The bonded (intact) links of the PRE faces that broke in tension (M8) since the last call, in slot
  /// order (element pairs, then element–wall faces), and the marks cleared (bond_breaks.cpp). `point`
  /// is the link's place on the face (ξ_i a along the face from its centre), `i`, `j` the element and
  /// the other element or the wall, as indices of the arrays.
  struct BondBreak {
    std::uint32_t i = 0, j = 0;
    bool wall = false;
    int segment = 0;
    double xi = 0.0;
    Vec2 point{};
  };
  std::vector<BondBreak> take_bond_breaks();

  /// The run's kinematic blow-up test, made inside the step by each thread over its elements: of the
  /// active elements whose increment of the last step exceeds numerics.max_step_fraction × radius, the one
  /// that moved farthest relative to its radius (the first with the largest (|Δx|/r)², or the first whose
  /// (|Δx|/r)² is NaN); index = npos if there is none.
  struct Overstep {
    static constexpr std::size_t npos = static_cast<std::size_t>(-1);
    std::size_t index = npos;
    double fraction2 = 0.0;  // (|Δx|/r)² of that element
  };
  Overstep overstep() const;

  /// Opens wall w (Wall::open): its contacts are dropped, it forms no new ones (a silo's gate, discharge.hpp).
  void open_wall(std::uint32_t w);

  /// The time-step limit over every contact the case can form, with what sets it and what it assumes
  /// (stability.hpp); the limit is infinity if no contact is possible.
  StabilityBound stability_bound() const;
  double stability_limit() const;
  std::int64_t rebuilds() const { return rebuilds_; }
  /// Rebuild tests over an element range that the travel bound showed needless (travel_ below; statistics).
  std::int64_t rebuild_tests_skipped() const { return rebuild_tests_skipped_; }
  /// The base plate's displacement and travel δ_B since the start (base_friction.hpp).
  const BasePlateTravel& plate_travel() const { return plate_travel_; }

  /// Threads used inside a step (1: none). Results do not depend on it, bit for bit: every element sums
  /// its contacts in the one-thread order, whatever thread computes what (thread_shares.hpp).
  /// A thread takes at least `min_per_thread` elements (a step of fewer elements is faster on one
  /// thread: the threads' start and barrier cost more than they save); tests lower it to 1.
  /// With `governed`, a step may use fewer of them while the machine is busy with other work
  /// (thread_governor.hpp; `dem2d run` turns it on unless --fixed-threads); without, exactly `threads`.
  void set_threads(int threads, std::size_t min_per_thread = 1024, bool governed = false) {
    tested_step_ = -1;
    threads_ = threads < 1 ? 1 : threads;
    min_per_thread_ = min_per_thread < 1 ? 1 : min_per_thread;
    governed_ = governed;
    governor_.start(1);  // restarted at the next step
  }
  int threads() const { return threads_; }
  /// The thread governor's statistics (probes, steps on fewer threads than asked for).
  const ThreadGovernor& governor() const { return governor_; }
  /// From the next step on, `threads` of the threads asked for, as the governor decides it (tests).
  void hold_threads(int threads) {
    governed_ = true;
    governor_.start(threads_asked());
    governor_.hold_at(threads);
  }
  /// Where a step's time goes, per thread and phase (step_timings.hpp); off by default (`run --timings`).
  void set_timings(bool on) { timings_.on = on; }
  StepTimings step_timings() const;
  /// The pool's waits, wake-ups and sleeps per thread (empty before a step on several threads).
  std::vector<PoolThreadTimes> pool_times() const { return workers_.pool ? workers_.pool->times() : std::vector<PoolThreadTimes>{}; }
  /// CPU time used so far by this simulation's worker threads (0 before a step on several threads) [s]; with
  /// the stepping thread's own clock, a run's CPU time even when other runs share the process (studies).
  double worker_cpu_seconds() const { return workers_.pool ? workers_.pool->cpu_seconds() : 0.0; }
  int threads_used() const;  // what a step uses: threads() limited by min_per_thread and the governor
  /// On several threads, a step measures each thread's CPU time on its share; every kBalanceSteps steps,
  /// if the busiest thread took more than kBalanceTolerance above the mean, the boundaries between the
  /// shares move so that the measured work is divided evenly (ThreadShares::balance). No result depends
  /// on where the boundaries lie. balance_threads does it at once with the given seconds per thread (tests
  /// use it to force any split); balances() counts the moves.
  static constexpr int kBalanceSteps = 32;
  /// The thread clock (CLOCK_THREAD_CPUTIME_ID) is a system call of about 1 µs on a KVM guest; it is read on
  /// every kClockEvery-th step only (8 of the 32 steps between two balance decisions).
  static constexpr int kClockEvery = 4;
  static constexpr double kBalanceTolerance = 0.03;
  void balance_threads(const std::vector<double>& seconds);
  std::int64_t balances() const { return balances_; }
  /// The element ranges of the threads' shares (threads_used() + 1 boundaries; empty before a step on
  /// several threads).
  const std::vector<std::uint32_t>& share_bounds() const { return shares_.first; }

  /// Element ids (Elements::id, what outputs show) and indices (where the element sits in the arrays now):
  /// equal unless numerics.reorder_every renumbered the elements in space (spatial_order.hpp).
  std::uint32_t index_of(std::uint32_t id) const { return index_of_id_.empty() ? id : index_of_id_[id]; }
  std::uint32_t id_of(std::size_t index) const {
    return m_.elements.id.empty() ? static_cast<std::uint32_t>(index) : m_.elements.id[index];
  }
  bool reordered() const { return !index_of_id_.empty(); }
  /// Brings the elements into the order of `ids` (ids[k]: the id of the element at index k), e.g. a
  /// checkpoint's; the contact slots follow. Throws std::invalid_argument unless ids is a permutation.
  void restore_order(const std::vector<std::uint32_t>& ids);

 private:
  friend struct SimulationAccess;  // checkpoints (run/checkpoint.cpp) save and restore the whole state
  // The threads that make a rebuild together: thread t of nt, all inside one job of pool (nullptr: one
  // thread). sync() is the pool's barrier.
  struct Team {
    WorkerThreads* pool = nullptr;
    int t = 0, nt = 1;
    void sync() const {
      if (pool) pool->barrier();
    }
  };
  // New candidates, slot lists, contact index and shares, on threads_used() threads (a job of its own).
  // The result is the same bit for bit for any number of threads.
  void rebuild();
  // The rebuild made by every thread of a job (a team of threads_used() threads, or of one); returns after
  // a barrier. The candidates and wall candidates are collected by element ranges, one per thread, and
  // joined in range order: the one-thread lists, element for element. The pair lists are merged by element
  // ranges (merge_on); the contact index and the shares are independent tasks, run at once on different
  // threads. false: too many slots for the contact index (on several threads the caller throws after the job:
  // an exception inside it would leave the other threads at a barrier).
  bool rebuild_on(const Team& team);
  // The element–wall candidates of elements [b, end), in (i, wall) order.
  void wall_candidates(std::uint32_t b, std::uint32_t end, std::vector<LinearSlot>& lin,
                       std::vector<FaceSlot>& face) const;
  void apply_preloads();
  bool needs_rebuild() const;
  double rebuild_limit2() const;  // the squared displacement that calls for a rebuild; < 0: rebuild now
  // The contact laws of slots [b, e): each writes its forces into its slot (and face_push_) and adds them
  // at once to its elements, in slot order: to every element (one thread, Shares = false), or only to the
  // elements that are not shared between threads (thread_shares.hpp; gather_forces sums the shared ones).
  // The disk-disk sweep in two stages one contact apart, and in AVX2 and plain builds (bench/journal.md,
  // "The disk–disk sweep in two stages").
  // Rolling: some law rolls (linear_pairs_.with_rolling); a model without rolling runs the sweep without its test.
  template <bool Shares, bool Rolling> DEM2D_CLONES_AVX2 void sweep_linear_pairs(double inv_dt, std::size_t b, std::size_t e);
  // The face sweeps in two builds, picked at start-up: plain x86-64 and AVX2 (three-operand VEX code, no
  // FMA: the same rounding bit for bit; bench/journal.md, "PRE faces: the segment loop"). g++ only: clang
  // (the sanitizer build) does not clone function templates.
  template <bool Shares> DEM2D_CLONES_AVX2 void sweep_face_pairs(double inv_dt, std::size_t b, std::size_t e);
  template <bool Shares> void sweep_linear_walls(double inv_dt, std::size_t b, std::size_t e);
  template <bool Shares> DEM2D_CLONES_AVX2 void sweep_face_walls(double inv_dt, std::size_t b, std::size_t e);
  void sweep_scatter(double inv_dt);  // one thread: every slot, scattering into the elements
  // Share `share` of a step on several threads: the slots its elements compute, scattered into its private
  // elements (from m g if from_weight, else onto the forces they hold); then, once the threads before it
  // have swept (WorkerThreads::wait_earlier), gather_shared sums its shared elements' slots in the fixed
  // order of the contact index.
  void sweep_share(double inv_dt, std::size_t share, bool from_weight);
  // step() on nt threads (parallel_step.cpp): the rebuild test, the sweeps, the sums of the shared elements
  // and, unless the base plate comes first, the integration, each thread over its share.
  void step_on_threads(int nt, bool tested, double inv_dt, double dt_v, double limit2_step, double limit2_next,
                       bool plate);
  void gather_shared(std::size_t share, bool from_weight);
  void gather_forces(const std::uint32_t* items, std::size_t count, bool from_weight);  // these elements
  void sum_wall_forces();
  void index_contacts();  // after every change of the slot lists (rebuild, restore)
  void index_others();   // the index beyond the linear pairs, the face push buffers and the thread shares
  void share_work(int threads);  // shares_ for this many threads (after index_contacts or set_threads)
  // How integrate_range may advance elements [b, e): every one active and free (one vectorised pass); the
  // active ones free, some removed from the run (the same pass with a select); or element by element.
  enum class Freedom : std::uint8_t { general, active_free, all_free };
  Freedom freedom(std::size_t b, std::size_t e) const;
  double velocity_dt() const;  // the step of (K17): Δt, or Δt/2 at a staggered start
  // What integrate_range found over its range for the next step's rebuild test: displaced (any_displaced,
  // unless the travel bound showed it needless: skipped), and the largest squared increment |Δx|² of an
  // active element (travel_).
  struct RangeTests {
    std::uint8_t displaced = 0, skipped = 0;
    double max_d2 = 0.0;
  };
  // (K17–K19) over elements [b, e), then the blow-up test over them (overstep()) and, if limit2_next >= 0,
  // the next step's rebuild test over them (tests).
  Overstep integrate_range(std::size_t b, std::size_t e, double dt_v, Freedom freedom, double limit2,
                           double limit2_next, RangeTests& tests);
  // The rebuild limit of the next step if it is known now (static walls, no base plate), else −1.
  double next_rebuild_limit2() const;
  // The step whose rebuild test the last integration made (displaced_); −1: none. Anything that may
  // change positions, references or walls between steps resets it (mutable model(), restores, reorders).
  std::int64_t tested_step_ = -1;
  void move_walls();
  void advance_base_plate();  // base friction (M21) forces, plate travel
  // A linear contact forms: its dashpots and the history it starts from.
  void start_linear(std::int32_t law, double overlap, double du_n, double du_s, double mass_i, double mass_j,
                    double& eta_n, double& eta_s, LinearContactHistory& h) const;
  // Its rolling constants and the moment it starts from (R1, R2, R5), if its law rolls; j: an element, or a
  // wall if `wall`. dtheta: the step's relative rotation increment.
  double linear_pair_rolling_moment(std::size_t k) const;  // slot k's rolling moment on i of the last step (R6)
  void start_rolling(const PairLaw& law, std::uint32_t i, std::uint32_t j, bool wall, double dtheta, RollingState& s) const;
  // The reference step's contacts, one slot each: its law and its forces added to its elements at once.
  void reference_linear_pair(std::size_t k, double inv_dt);
  void reference_face_pair(std::size_t k, double inv_dt);
  void reference_linear_wall(std::size_t k, double inv_dt);
  void reference_face_wall(std::size_t k, double inv_dt);
  // Polygon elements (polygon_sweep.cpp, docs/model.md §5): a model with polygons steps on one thread.
  void check_polygon_model();  // sets polygons_; throws std::invalid_argument on what they do not support
  void rebuild_polygons();     // their slots from the candidates and the walls, histories kept
  void sweep_polygons(double inv_dt);  // (P5–P8) and (K6–K14) at every contact point; after the other sweeps
  void advance_corners(PolygonSlot& s, std::uint32_t a, std::uint32_t b, bool wall, double inv_dt);
  double polygon_elastic_energy() const;
  void polygon_contacts(std::vector<ContactView>& out) const;
  const PolygonSlot* polygon_slot(std::uint32_t i, std::uint32_t j, bool wall) const;  // touching, or nullptr
  bool polygons_ = false;
  // Gap springs (gap_springs.cpp, docs/model.md §6): bonds formed at the start between disks whose law has
  // `gap`; a model with them steps on one thread, their sweep after the other sweeps.
  void form_gap_springs();  // throws std::invalid_argument on what they do not support
  void sweep_gap_springs(double inv_dt);  // (B2–B5)
  double gap_spring_energy() const;
 public:
  /// The gap springs (B1): formed at the start, in (i, j) order; `intact` false once broken.
  const std::vector<GapSpring>& gap_springs() const { return gap_springs_; }
  std::size_t gap_springs_intact() const;

 private:
  std::vector<GapSpring> gap_springs_;
  std::vector<PolygonSlot> polygon_pairs_, polygon_walls_;  // sorted by (i, j)
  std::vector<CornerHit> hits_;                             // sweep scratch
  std::vector<CornerSlot> corner_scratch_;
  std::vector<std::vector<Vec2>> corner_cache_;  // per polygon shape: its corners in the world this step

  Model m_;
  NeighbourSearch search_;
  std::vector<CandidatePair> candidates_;
  LinearPairSlots linear_pairs_;           // merged in place at a rebuild (no second list)
  std::vector<LinearSlot> linear_walls_;
  std::vector<FaceSlot> face_pairs_, face_walls_;
  std::vector<LinearSlot> linear_fresh_;  // rebuild scratch (wall candidates), kept to reuse its capacity
  std::vector<FaceSlot> face_fresh_;
  struct RebuildPart {  // rebuild scratch of thread t > 0 (thread 0 writes into the lists above directly)
    std::vector<CandidatePair> pairs;
    std::vector<LinearSlot> lin;
    std::vector<FaceSlot> face;
    std::size_t at_pairs = 0, at_lin = 0, at_face = 0;  // where the part goes in the joined lists
    std::vector<std::pair<std::size_t, FullPairSlot>> linear_aside;  // merge_on's slots held aside
    std::vector<std::pair<std::size_t, FaceSlot>> face_aside;
  };
  MergePlan linear_plan_, face_plan_;
  std::vector<RebuildPart> rebuild_parts_;
  mutable std::vector<Energies> energy_chunks_;  // energies(): the sums of its chunks
  std::vector<std::uint32_t> rebuild_first_;  // the element ranges of a rebuild's threads
  bool rebuild_cells_ = false;                // the neighbour search has cells (two or more active elements)
  ContactIndex index_;                        // each element's slots in the fixed summation order
  ThreadShares shares_;                       // which thread computes what (built for threads_used())
  // The threads of a step, started at the first step on several threads; a copy of the simulation
  // starts its own.
  struct Workers {
    std::unique_ptr<WorkerThreads> pool;
    Workers() = default;
    Workers(const Workers&) {}
    Workers& operator=(const Workers&) { return *this; }
    Workers(Workers&&) noexcept = default;
    Workers& operator=(Workers&&) noexcept = default;
  } mutable workers_;
  WorkerThreads& workers(int threads) const;  // the pool (started on first use; energies() uses it too)
  std::vector<std::uint8_t> displaced_;  // per thread: an element of its share moved far enough to rebuild
  // per thread: the same, from a rebuild test made at the start of a step on several threads. Not displaced_:
  // a thread that has passed the test's barrier goes on to write displaced_ for the next step while a slower
  // thread may still be reading the test's flags (it then saw "rebuild" alone and waited for ever in it).
  std::vector<std::uint8_t> displaced_now_;
  std::vector<Overstep> oversteps_;      // per thread: the blow-up test over its share (overstep())
  struct alignas(64) ThreadClock {       // per thread: CPU seconds on its share since the shares were made
    double seconds = 0.0;
  };
  std::vector<ThreadClock> busy_;
  std::vector<double> busy_seconds_;     // scratch for balance_threads
  int balance_steps_ = 0;                // steps measured in busy_
  double balance_seconds_ = 0.0;         // the wall time of the last balance (balance_if_uneven: made when it pays)
  std::int64_t balances_ = 0;
  void balance_if_uneven();
  std::vector<ElementPush> face_push_, face_wall_push_;  // this step's face forces on the elements
  int threads_ = 1;
  std::size_t min_per_thread_ = 1024;
  int threads_asked() const;  // threads() limited by min_per_thread (the governor's most)
  bool governed_ = false;
  ThreadGovernor governor_;
  double governor_wait0_ = 0.0, governor_job0_ = 0.0;  // the pool's totals at the window's start
  void govern(double step_wall);                        // after a step (thread_governor.hpp)
  mutable StepTimings timings_;                         // (set_timings)
  PhaseTimes* phases(int t) { return timings_.on ? &timings_.threads[static_cast<std::size_t>(t)] : nullptr; }
  std::vector<double> x_ref_, y_ref_;  // positions at the last rebuild
  // The travel bound: no element is farther than travel_ from its reference position (x_ref_, y_ref_): the
  // sum over the steps since the last rebuild of the step's largest increment |Δx| plus the rounding of
  // x += Δx (kRoundoff times the largest coordinate; triangle inequality). The rebuild test made right after
  // an integration (static walls, no base plate) is skipped while travel_ plus the step's largest increment
  // stays below kTravelMargin √limit2: the exact test could only say "no", so when rebuilds happen, and every
  // result, is unchanged (the margin covers the relative rounding of the sums and of the test). ∞: unknown
  // (a restored state, a reordering, a model changed from outside such as disks removed at an outlet, the
  // base plate's second pass), the exact test every step until the next rebuild.
  static constexpr double kTravelUnknown = std::numeric_limits<double>::infinity();
  static constexpr double kTravelMargin = 0.9;
  static constexpr double kRoundoff = 0x1p-52;
  double travel_ = kTravelUnknown;
  std::vector<RangeTests> range_tests_;  // per thread: its ranges' tests in this step (displaced_ aside)
  std::int64_t rebuild_tests_skipped_ = 0;
  std::vector<Vec2> wall_ref_;
  double skin_ = 0.0;
  double time_ = 0.0;
  std::int64_t step_ = 0;
  bool keep_forces_ = true;        // keep_contact_forces
  std::int64_t forces_step_ = 0;   // the step whose contact resultants the slots hold (−1: none)
  void require_contact_forces(const char* reader) const;
  std::int64_t rebuilds_ = 0;
  BasePlateTravel plate_travel_;
  bool preloading_ = false;  // the static zeroth step of apply_preloads()
  // Spatial reordering (spatial_order.cpp): at a rebuild every numerics.reorder_every rebuilds.
  void reorder_elements();
  void apply_order();  // order_ → elements, slots, candidates, index_of_id_
  std::vector<std::uint32_t> order_, new_of_old_, index_of_id_;  // index_of_id_ empty: ids = indices
  std::vector<std::uint64_t> order_keys_;
  PermuteScratch permute_scratch_;
};

}  // namespace dem
