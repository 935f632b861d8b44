// The brush as a population (brush.method = "population", docs/brush.md): the brush's force, torque
// and power as sums over its drawn filaments of per-filament values interpolated from a few
// representative filaments, run to their steady state on a grid of lengths × diameters refined
// where the sums need it.
//
// The interpolant is bilinear on the grid's nodes. Each axis is a set of cells [a, b] whose midpoint
// m is a node as well; a cell's indicator is what m changed in the brush's sums,
//   Δ = Σ_k hat_m(x_k)·(g(m) − (g(a) + g(b))/2)   over the filaments k inside the cell,
// with g the value interpolated along the other axis at the filament. The estimate of the error left
// is Σ|Δ| over the cells: for a smooth g the interpolant's error over a cell is Δ/3 (linear
// interpolation's error falls by 4 when the cell is halved), but where the orbit changes inside a
// cell (an impact more or less a revolution puts a kink or a step into g) it falls only by 2 or not
// at all, and Δ itself is the honest figure. Cells whose indicators hold at least half of the total
// are split (Dörfler's marking) until the estimated error of the mean normal force and of the hub
// torque is below brush.population_tolerance, or brush.population_max_runs is reached (then the
// summary says the tolerance was not met).
//
// The grid spans the filaments that reach the surface, from the shortest of them: a filament that
// barely reaches may strike hard (one impact a revolution at nearly the full tip speed can deliver
// more than many shallow contacts), so the force does not vanish continuously at zero depth and is
// not extrapolated there. Filaments too short to reach deliver nothing and run nothing.
#include "brush_filament.hpp"

#include "rotbeam/case.hpp"
#include "rotbeam/job_runner.hpp"
#include "rotbeam/units.hpp"

#include <unsupported/Eigen/FFT>

#include <algorithm>
#include <array>
#include <complex>
#include <cmath>
#include <cstdio>
#include <map>
#include <mutex>

namespace rotbeam::detail {

namespace {

// A cell of an axis: its ends and midpoint (all nodes of the axis).
struct Cell {
  double a = 0, m = 0, b = 0;
};

// One axis of the grid: its sorted nodes and its leaf cells (none for a single node).
struct Axis {
  std::vector<double> nodes;
  std::vector<Cell> cells;

  static Axis over(double lo, double hi, int cells) {
    Axis x;
    if (!(hi > lo)) {
      x.nodes = {lo};
      return x;
    }
    const double h = (hi - lo) / cells;
    for (int c = 0; c < cells; ++c) {
      const double a = lo + c * h, b = c + 1 == cells ? hi : lo + (c + 1) * h;
      x.cells.push_back({a, 0.5 * (a + b), b});
      x.nodes.push_back(a);
      x.nodes.push_back(0.5 * (a + b));
    }
    x.nodes.push_back(hi);
    return x;
  }
  // The interval of nodes holding v and the weight of its right node (0 on a single node).
  std::pair<int, double> locate(double v) const {
    if (nodes.size() < 2) return {0, 0.0};
    const auto it = std::upper_bound(nodes.begin(), nodes.end(), v);
    int i = static_cast<int>(it - nodes.begin()) - 1;
    i = std::clamp(i, 0, static_cast<int>(nodes.size()) - 2);
    const double t = (v - nodes[i]) / (nodes[i + 1] - nodes[i]);
    return {i, std::clamp(t, 0.0, 1.0)};
  }
  int index_of(double v) const {
    return static_cast<int>(std::lower_bound(nodes.begin(), nodes.end(), v) - nodes.begin());
  }
  // Splits cell c into two, whose midpoints are new nodes.
  void split(std::size_t c) {
    const Cell cell = cells[c];
    const Cell left{cell.a, 0.5 * (cell.a + cell.m), cell.m}, right{cell.m, 0.5 * (cell.m + cell.b), cell.b};
    cells[c] = left;
    cells.push_back(right);
    nodes.insert(std::upper_bound(nodes.begin(), nodes.end(), left.m), left.m);
    nodes.insert(std::upper_bound(nodes.begin(), nodes.end(), right.m), right.m);
  }
};

// A cell marked for refinement: its share of the estimate, where it is, and the filaments inside it
// that are interpolated (not run on their own).
struct Mark {
  double eta = 0;
  int axis = 0;
  std::size_t cell = 0;
  int filaments = 0;
};

// A refinement the marking may take: split a cell (axis 0 or 1) or run one filament on its own
// (axis −1, `cell` its index), with the share of the estimate it addresses and what it costs in runs.
struct Action {
  double benefit = 0;
  int cost = 1;
  int axis = 0;
  std::size_t cell = 0;
};

// The quantities the refinement watches: mean normal force, tangential force and hub torque.
constexpr int kWatched = 3;
using Watched = std::array<double, kWatched>;

Watched watched(const FilamentSteadyState& s) {
  return {s.mean_normal_force_n, s.mean_tangential_force_n, s.mean_hub_torque_n_m};
}

// A node of the grid and its run (or the stand-in of the filaments that do not reach).
struct Node {
  double length_m = 0, diameter_m = 0;
  bool zero = false;  // the stand-in of the filaments that do not reach: zero values, not run
  FilamentOrbit orbit;
  int source = -1;    // whose values stand in for it in the estimate (itself, or for a failed run the nearest finished node)
};

class Population {
public:
  Population(const Config& config, const BrushOptions& options, BrushResult& result)
      : config_(config), options_(options), result_(result), start_(clock_s()) {}

  void run();

private:
  // The node at (length, diameter), created (not yet run) when new.
  int node_at(double length, double diameter) {
    const auto key = std::make_pair(length, diameter);
    const auto it = index_.find(key);
    if (it != index_.end()) return it->second;
    Node n;
    n.length_m = length;
    n.diameter_m = diameter;
    nodes_.push_back(std::move(n));
    const int id = static_cast<int>(nodes_.size()) - 1;
    index_.emplace(key, id);
    pending_.push_back(id);
    return id;
  }
  int real_runs() const {
    int n = 0;
    for (const Node& node : nodes_) n += !node.zero;
    return n;
  }
  void add_grid() {
    for (double l : lengths_.nodes)
      for (double d : diameters_.nodes) node_at(l, d);
  }
  void run_pending();
  void fill_sources();
  Watched value(int node) const {
    const Node& n = nodes_[node];
    if (n.zero || n.source < 0) return {0, 0, 0};
    return watched(nodes_[n.source].orbit.state);
  }
  // Bilinear weights of a filament on the grid: up to four (node, weight).
  std::array<std::pair<int, double>, 4> weights(double length, double diameter) const;
  Watched interpolate(double length, double diameter) const {
    Watched v{};
    for (const auto& [node, w] : weights(length, diameter))
      if (w != 0.0) {
        const Watched n = value(node);
        for (int q = 0; q < kWatched; ++q) v[q] += w * n[q];
      }
    return v;
  }
  // One refinement round's indicators; true when the estimate meets the tolerance.
  bool estimate(std::vector<Mark>& marks);
  bool failed(int node) const { return !nodes_[node].zero && !nodes_[node].orbit.state.ran; }
  // The share of a filament's interpolation on nodes whose run failed (0 for one run on its own).
  double failed_weight(const BrushFilament& f) const {
    if (exact_node_[f.index] >= 0) return 0.0;
    double w = 0;
    for (const auto& [node, weight] : weights(f.length_m, f.diameter_m))
      if (weight != 0.0 && failed(node)) w += weight;
    return w;
  }
  // Whether the filament counts as failed: its own run failed, or its interpolation leans on a run
  // that did (as the filament route, which leaves a failed filament out of every sum).
  bool counts_failed(const BrushFilament& f) const {
    const int own = exact_node_[f.index];
    return own >= 0 ? failed(own) : failed_weight(f) > 0.0;
  }
  // The filament's values: its own run's where it was run on its own, else interpolated (a failed
  // node's values are its nearest finished neighbour's, fill_sources).
  Watched value_of(const BrushFilament& f) const {
    const int own = exact_node_[f.index];
    return own >= 0 ? value(own) : interpolate(f.length_m, f.diameter_m);
  }
  // Runs one filament on its own (its values then its own, not interpolated).
  void run_filament(const BrushFilament& f);
  void assemble();

  const Config& config_;
  const BrushOptions& options_;
  BrushResult& result_;
  double start_;
  Axis lengths_, diameters_;
  std::vector<Node> nodes_;
  std::map<std::pair<double, double>, int> index_;
  std::vector<int> pending_;
  std::vector<const BrushFilament*> reaching_, by_length_, by_diameter_;
  std::vector<int> exact_node_;       // by filament index: the node of its own run, or −1 (interpolated)
  std::vector<double> contribution_;  // by filament index: its share of the last estimate (Σ over its cells)
  double failure_doubt_ = 0;          // the last estimate's share from filaments interpolated on failed runs
  PopulationEstimate estimate_;
  BrushProgress progress_;
};

std::array<std::pair<int, double>, 4> Population::weights(double length, double diameter) const {
  const auto [i, t] = lengths_.locate(length);
  const auto [j, s] = diameters_.locate(diameter);
  const auto at = [&](int a, int b) {
    return index_.at(std::make_pair(lengths_.nodes[a], diameters_.nodes[b]));
  };
  const int i1 = lengths_.nodes.size() > 1 ? i + 1 : i, j1 = diameters_.nodes.size() > 1 ? j + 1 : j;
  return {std::make_pair(at(i, j), (1 - t) * (1 - s)), std::make_pair(at(i1, j), t * (1 - s)),
          std::make_pair(at(i, j1), (1 - t) * s), std::make_pair(at(i1, j1), t * s)};
}

void Population::run_pending() {
  if (pending_.empty()) return;
  std::vector<int> todo;
  todo.swap(pending_);
  std::vector<Config> configs(todo.size());
  const double l0 = config_.beam.length_m, p0 = config_.surface.depth_fraction;
  for (std::size_t j = 0; j < todo.size(); ++j) {
    Node& n = nodes_[todo[j]];
    BrushFilament f;
    f.length_m = n.length_m;
    f.diameter_m = n.diameter_m;
    f.depth_fraction = n.length_m == l0 ? p0 : (n.length_m - l0 + p0 * l0) / n.length_m;
    try {
      configs[j] = filament_config(config_, f);
    } catch (const ConfigError& e) {
      char what[200];
      std::snprintf(what, sizeof what, "brush: the representative filament L = %.6g m, D = %.6g m (depth fraction %.6g): ",
                    f.length_m, f.diameter_m, f.depth_fraction);
      throw ConfigError(what + std::string(e.what()));
    }
  }
  progress_.total += static_cast<int>(todo.size());
  std::mutex mutex;
  JobRunnerOptions runner;
  runner.threads = options_.threads;
  runner.stop = options_.stop;
  run_jobs(
      todo.size(),
      [&](std::size_t j) {
        FilamentOrbit orbit = run_filament_orbit(configs[j], options_.stop);
        std::lock_guard<std::mutex> lock(mutex);
        nodes_[todo[j]].orbit = std::move(orbit);
        ++progress_.finished;
        progress_.elapsed_s = clock_s() - start_;
        progress_.eta_s = progress_.elapsed_s / progress_.finished * (progress_.total - progress_.finished);
        if (options_.on_progress) options_.on_progress(progress_);
      },
      runner);
  // A job the stop kept from starting left its node's state as never run (ran = false).
  fill_sources();
}

// A failed node's values are its nearest finished node's along the length axis (the same diameter),
// else along the diameter axis; counted failed all the same (its filaments' status says so).
void Population::fill_sources() {
  for (std::size_t k = 0; k < nodes_.size(); ++k) {
    Node& n = nodes_[k];
    if (n.zero || n.orbit.state.ran) {
      n.source = static_cast<int>(k);
      continue;
    }
    n.source = -1;
    double best = INFINITY;
    for (std::size_t o = 0; o < nodes_.size(); ++o) {
      const Node& c = nodes_[o];
      if (c.zero || !c.orbit.state.ran) continue;
      const double dl = std::abs(c.length_m - n.length_m) / config_.beam.length_m;
      const double dd = std::abs(c.diameter_m - n.diameter_m) / config_.beam.diameter_m;
      const double distance = dd == 0.0 ? dl : 1e6 + dd + dl;  // the same diameter first
      if (distance < best) best = distance, n.source = static_cast<int>(o);
    }
  }
}

void Population::run_filament(const BrushFilament& f) {
  if (exact_node_[f.index] >= 0) return;
  Node n;
  n.length_m = f.length_m;
  n.diameter_m = f.diameter_m;
  nodes_.push_back(std::move(n));
  exact_node_[f.index] = static_cast<int>(nodes_.size()) - 1;
  pending_.push_back(exact_node_[f.index]);
  ++estimate_.exact_filaments;
}

bool Population::estimate(std::vector<Mark>& marks) {
  // The sums as they stand: the filaments that count as failed are left out, as in the result.
  Watched sum{}, doubt{};
  bool unresolved_failure = false;
  for (const BrushFilament* f : reaching_) {
    const Watched v = value_of(*f);
    if (!counts_failed(*f)) {
      for (int q = 0; q < kWatched; ++q) sum[q] += v[q];
    } else if (exact_node_[f->index] < 0) {
      // Interpolated on a failed run: unknown until the filament is run on its own.
      unresolved_failure = true;
      for (int q = 0; q < kWatched; ++q) doubt[q] += std::abs(v[q]);
    }
  }
  Watched error{};
  marks.clear();
  std::fill(contribution_.begin(), contribution_.end(), 0.0);
  failure_doubt_ = 0;
  const auto scale = [&](int q) { return std::max(std::abs(sum[q]) + doubt[q], 1e-300); };
  // A filament interpolated on a failed run adds its stand-in value's magnitude to the error (all of
  // it when nothing stands in), and is a candidate to run on its own.
  for (const BrushFilament* f : reaching_) {
    if (exact_node_[f->index] >= 0 || !counts_failed(*f)) continue;
    const Watched v = value_of(*f);
    double own = 0;
    for (int q = 0; q < kWatched; ++q) {
      error[q] += std::abs(v[q]);
      if (q != 1) own = std::max(own, std::abs(v[q]) / scale(q));
    }
    contribution_[f->index] += std::max(own, 1e-12);
    failure_doubt_ += std::max(own, 1e-12);
  }
  for (int axis = 0; axis < 2; ++axis) {
    const Axis& ax = axis == 0 ? lengths_ : diameters_;
    for (std::size_t c = 0; c < ax.cells.size(); ++c) {
      const Cell& cell = ax.cells[c];
      const double half = 0.5 * (cell.b - cell.a);
      Watched delta{};
      // The filaments inside the cell, from the axis's sorted order. Interpolated at a node of this
      // axis, the interpolant is the other axis's interpolation along that node's line (g).
      const std::vector<const BrushFilament*>& sorted = axis == 0 ? by_length_ : by_diameter_;
      const auto key = [axis](const BrushFilament* f) { return axis == 0 ? f->length_m : f->diameter_m; };
      auto it = std::upper_bound(sorted.begin(), sorted.end(), cell.a,
                                 [&](double v, const BrushFilament* f) { return v < key(f); });
      int inside = 0;
      for (; it != sorted.end() && key(*it) < cell.b; ++it) {
        const BrushFilament* f = *it;
        if (exact_node_[f->index] >= 0 || counts_failed(*f)) continue;  // run on its own, or counted above
        ++inside;
        const double x = key(f);
        const double hat = 1.0 - std::abs(x - cell.m) / half;
        const auto at = [&](double node) {
          return axis == 0 ? interpolate(node, f->diameter_m) : interpolate(f->length_m, node);
        };
        const Watched gm = at(cell.m), ga = at(cell.a), gb = at(cell.b);
        double own = 0;
        for (int q = 0; q < kWatched; ++q) {
          const double d = hat * (gm[q] - 0.5 * (ga[q] + gb[q]));
          delta[q] += d;
          if (q != 1) own = std::max(own, std::abs(d) / scale(q));
        }
        contribution_[f->index] += own;
      }
      double eta = 0;
      for (int q = 0; q < kWatched; ++q) {
        error[q] += std::abs(delta[q]);
        if (q != 1) eta = std::max(eta, std::abs(delta[q]) / scale(q));  // the tangential force is not steered on
      }
      const double width = (cell.b - cell.a) / (axis == 0 ? config_.beam.length_m : config_.beam.diameter_m);
      if (eta > 0.0 && width > 1e-9) marks.push_back({eta, axis, c, inside});
    }
  }
  for (int q = 0; q < kWatched; ++q)
    if (unresolved_failure && !(error[q] > 0.0)) error[q] = scale(q);  // nothing stands in: all in doubt
  estimate_.normal_force_error = error[0] / scale(0);
  estimate_.tangential_force_error = error[1] / scale(1);
  estimate_.hub_torque_error = error[2] / scale(2);
  return !unresolved_failure && estimate_.normal_force_error <= estimate_.tolerance &&
         estimate_.hub_torque_error <= estimate_.tolerance;
}

void Population::run() {
  const BrushSettings& b = *config_.brush;
  estimate_.tolerance = b.population_tolerance;
  result_.filaments = brush_filaments(config_);
  for (BrushFilament& f : result_.filaments) {
    f.group = 0;
    if (f.depth_fraction > 0.0) reaching_.push_back(&f);
  }
  exact_node_.assign(result_.filaments.size(), -1);
  contribution_.assign(result_.filaments.size(), 0.0);
  by_length_ = by_diameter_ = reaching_;
  std::stable_sort(by_length_.begin(), by_length_.end(),
                   [](const BrushFilament* a, const BrushFilament* b) { return a->length_m < b->length_m; });
  std::stable_sort(by_diameter_.begin(), by_diameter_.end(),
                   [](const BrushFilament* a, const BrushFilament* b) { return a->diameter_m < b->diameter_m; });
  if (!reaching_.empty()) {
    const double l0 = config_.beam.length_m, p0 = config_.surface.depth_fraction;
    double l_lo = INFINITY, l_hi = -INFINITY, d_lo = INFINITY, d_hi = -INFINITY;
    for (const BrushFilament* f : reaching_) {
      l_lo = std::min(l_lo, f->length_m), l_hi = std::max(l_hi, f->length_m);
      d_lo = std::min(d_lo, f->diameter_m), d_hi = std::max(d_hi, f->diameter_m);
    }
    lengths_ = Axis::over(l_lo, l_hi, 2);
    diameters_ = Axis::over(d_lo, d_hi, 1);
    if (reaching_.size() <= lengths_.nodes.size() * diameters_.nodes.size()) {
      // No more filaments than the first grid has nodes: each runs on its own (the filament route).
      for (const BrushFilament* f : reaching_) run_filament(*f);
      lengths_ = Axis{}, diameters_ = Axis{};
    } else {
      add_grid();
    }
    run_pending();
    std::vector<Mark> marks;
    for (;;) {
      if (options_.stop && options_.stop->stop_requested()) break;
      ++estimate_.rounds;
      if (estimate(marks)) {
        estimate_.converged = true;
        break;
      }
      // Dörfler's marking within the budget, by what each action addresses per run: a cell split (its
      // two halves' midpoints run along every line of the other axis), or one filament run on its
      // own — where a few filaments hold a cell's error (the force's spike where a filament barely
      // reaches) running them costs less than splitting the cell round them.
      double total = failure_doubt_;
      std::vector<Action> actions;
      for (const Mark& m : marks) {
        total += m.eta;
        actions.push_back({m.eta, 2 * static_cast<int>(m.axis == 0 ? diameters_.nodes.size() : lengths_.nodes.size()),
                           m.axis, m.cell});
      }
      for (const BrushFilament* f : reaching_)
        if (contribution_[f->index] > 0.0) actions.push_back({contribution_[f->index], 1, -1, static_cast<std::size_t>(f->index)});
      std::stable_sort(actions.begin(), actions.end(), [](const Action& x, const Action& y) {
        return x.benefit * y.cost > y.benefit * x.cost;
      });
      std::vector<std::pair<int, std::size_t>> split;
      std::vector<std::size_t> alone;
      double taken = 0;
      int runs = real_runs(), split_axis = -1;
      for (const Action& a : actions) {
        if (runs + a.cost > b.population_max_runs) continue;  // a cheaper action may still fit
        // Splits along both axes in one round would also run their crossings: one axis a round.
        if (a.axis >= 0 && split_axis >= 0 && a.axis != split_axis) continue;
        if (a.axis >= 0) split_axis = a.axis;
        runs += a.cost;
        (a.axis < 0 ? alone.push_back(a.cell) : split.push_back({a.axis, a.cell}));
        taken += a.benefit;
        if (taken >= 0.5 * total) break;
      }
      if (split.empty() && alone.empty()) break;  // the budget is spent
      // Never more runs than running every interpolated filament on its own would take.
      std::size_t interpolated = 0;
      for (const BrushFilament* f : reaching_) interpolated += exact_node_[f->index] < 0;
      if (interpolated <= static_cast<std::size_t>(runs - real_runs()) &&
          real_runs() + static_cast<int>(interpolated) <= b.population_max_runs) {
        for (const BrushFilament* f : reaching_) run_filament(*f);
        run_pending();
        continue;
      }
      for (const std::size_t k : alone) run_filament(result_.filaments[k]);
      // Split the highest cell indices first so that earlier indices stay valid.
      std::sort(split.begin(), split.end(), [](const auto& x, const auto& y) { return x > y; });
      for (const auto& [axis, c] : split) (axis == 0 ? lengths_ : diameters_).split(c);
      add_grid();
      run_pending();
    }
  }
  assemble();
}

void Population::assemble() {
  const double omega = rad_per_s_from_rpm(config_.beam.speed_rpm);
  // The filaments run: every node of the grid, the filaments run on their own, and a stand-in (not
  // run) for the filaments that do not reach the surface, at the length that just reaches it.
  const double l0 = config_.beam.length_m, p0 = config_.surface.depth_fraction;
  if (reaching_.size() < result_.filaments.size()) {
    Node n;
    n.length_m = l0 * (1.0 - p0);
    n.diameter_m = config_.beam.diameter_m;
    n.zero = true;
    nodes_.push_back(std::move(n));
  }
  const std::size_t count = nodes_.size();
  result_.distinct.assign(count, FilamentSteadyState{});
  result_.run.assign(count, RunFilament{});
  for (std::size_t k = 0; k < count; ++k) {
    const Node& n = nodes_[k];
    RunFilament& r = result_.run[k];
    r.length_m = n.length_m;
    r.diameter_m = n.diameter_m;
    r.depth_fraction = n.zero ? 0.0 : n.length_m == l0 ? p0 : (n.length_m - l0 + p0 * l0) / n.length_m;
    if (n.zero)
      result_.distinct[k].reaches = false;
    else
      result_.distinct[k] = n.orbit.state;
  }
  // Each filament: its weights on the nodes, its estimates, its nearest node run. A filament that
  // counts as failed (its own run failed, or its interpolation leans on one that did) is left out of
  // every sum and table, as the filament route leaves out a filament that failed.
  result_.estimates.assign(result_.filaments.size(), FilamentEstimate{});
  // Phases to the nearest quarter of output.bin_deg.
  const int cells = std::max(1, static_cast<int>(std::lround(360.0 / config_.simulation.bin_deg))) * 4;
  const double cell_deg = 360.0 / cells;
  std::vector<std::vector<double>> phases(count);  // per node: the weights of its filaments' phases, by fine cell
  for (BrushFilament& f : result_.filaments) {
    if (!(f.depth_fraction > 0.0)) {
      f.group = static_cast<int>(count) - 1;  // the stand-in, last
      ++result_.run[f.group].nearest;
      result_.run[f.group].weight += 1.0;
      continue;
    }
    const int own = exact_node_[f.index];
    const std::array<std::pair<int, double>, 4> weights_of =
        own >= 0 ? std::array<std::pair<int, double>, 4>{{{own, 1.0}, {own, 0.0}, {own, 0.0}, {own, 0.0}}}
                 : weights(f.length_m, f.diameter_m);
    if (counts_failed(f)) {
      int worst = own;
      double worst_w = -1;
      for (const auto& [node, w] : weights_of)
        if (w > worst_w && failed(node)) worst = node, worst_w = w;
      f.group = worst;
      ++result_.run[worst].nearest;
      continue;
    }
    FilamentEstimate& e = result_.estimates[f.index];
    int nearest = -1;
    double nearest_w = -1;
    const int cell = ((static_cast<int>(std::lround(f.phase_deg / cell_deg)) % cells) + cells) % cells;
    for (const auto& [node, w] : weights_of) {
      if (w == 0.0) continue;
      if (w > nearest_w) nearest = node, nearest_w = w;
      result_.run[node].weight += w;
      auto& ph = phases[node];
      if (ph.empty()) ph.assign(cells, 0.0);
      ph[cell] += w;
      const FilamentSteadyState& s = nodes_[node].orbit.state;
      e.mean_normal_force_n += w * s.mean_normal_force_n;
      e.mean_tangential_force_n += w * s.mean_tangential_force_n;
      e.mean_hub_torque_n_m += w * s.mean_hub_torque_n_m;
      e.impacts_per_revolution += w * s.impacts_per_revolution;
      e.contact_time_s += w * s.contact_time_s;
      e.peak_normal_force_n += w * s.peak_normal_force_n;
      e.max_tip_deflection_ratio += w * s.max_tip_deflection_ratio;
      e.ledger_residual_max_j += w * s.ledger_residual_max_j;
    }
    e.mean_hub_power_w = e.mean_hub_torque_n_m * omega;
    f.group = nearest;
    ++result_.run[nearest].nearest;
  }
  // The workpiece: each node's orbit at its own angle on fine cells, correlated round the revolution
  // with its filaments' phases (a filament at phase cell j reaches own cell c when the reference is
  // at c − j: REF = OWN · conj(PHASES) in Fourier space, Eigen's FFT) and summed; the profile at the
  // own angle.
  ForceBins total(config_.simulation.bin_deg, omega), profile(config_.simulation.bin_deg, omega);
  constexpr int kChannels = 4;  // normal, tangential, hub, impacts
  std::array<std::vector<double>, kChannels> own_cells;
  std::array<std::vector<std::complex<double>>, kChannels> sum;
  for (int ch = 0; ch < kChannels; ++ch) own_cells[ch].assign(cells, 0.0), sum[ch].assign(cells, 0.0);
  std::vector<std::complex<double>> spectrum(cells), phase_spectrum(cells);
  Eigen::FFT<double> fft;
  for (std::size_t k = 0; k < nodes_.size(); ++k) {
    const Node& n = nodes_[k];
    if (n.zero || !n.orbit.state.ran || phases[k].empty()) continue;
    const FilamentOrbit& orbit = n.orbit;
    const double weight_all = result_.run[k].weight;
    for (auto& c : own_cells) std::fill(c.begin(), c.end(), 0.0);
    for (const MomentumDelivery& d : orbit.deliveries) {
      profile.add(d, 0.0, orbit.weight * weight_all);
      // The delivery on the fine cells of its own angle, spread uniformly over what it spans.
      const double from = d.from_deg + 180.0;
      const int first = static_cast<int>(std::floor(from / cell_deg));
      if (!(d.span_deg > 0.0)) {
        const int c = ((first % cells) + cells) % cells;
        own_cells[0][c] += orbit.weight * d.normal_n_s, own_cells[1][c] += orbit.weight * d.tangential_n_s;
        own_cells[2][c] += orbit.weight * d.hub_angular_impulse_n_m_s;
        if (d.impact) own_cells[3][c] += orbit.weight;
        continue;
      }
      const double to = from + d.span_deg;
      for (int c = first; c * cell_deg < to; ++c) {
        const double lo = std::max(from, c * cell_deg), hi = std::min(to, (c + 1) * cell_deg);
        if (!(hi > lo)) continue;
        const double share = (hi - lo) / d.span_deg * orbit.weight;
        const int w = ((c % cells) + cells) % cells;
        own_cells[0][w] += share * d.normal_n_s, own_cells[1][w] += share * d.tangential_n_s;
        own_cells[2][w] += share * d.hub_angular_impulse_n_m_s;
      }
    }
    fft.fwd(phase_spectrum, phases[k]);
    for (int ch = 0; ch < kChannels; ++ch) {
      fft.fwd(spectrum, own_cells[ch]);
      for (int m = 0; m < cells; ++m) sum[ch][m] += spectrum[m] * std::conj(phase_spectrum[m]);
    }
  }
  std::array<std::vector<double>, kChannels> reference;
  double largest = 0;
  for (int ch = 0; ch < kChannels; ++ch) {
    fft.inv(reference[ch], sum[ch]);
    for (double v : reference[ch]) largest = std::max(largest, std::abs(v));
  }
  // The transform's round-off (≈ 1e-16 of the largest cell) is not momentum: below 1e-13 of it a
  // cell is empty, as it is in the filament route.
  const double floor = 1e-13 * largest;
  const auto clean = [floor](double v) { return std::abs(v) <= floor ? 0.0 : v; };
  for (int r = 0; r < cells; ++r) {
    const double normal = clean(reference[0][r]), tangential = clean(reference[1][r]), hub = clean(reference[2][r]);
    if (normal != 0.0 || tangential != 0.0 || hub != 0.0)
      total.add_spread(-180.0 + r * cell_deg, cell_deg, normal, tangential, hub);
    total.add_impacts(-180.0 + (r + 0.5) * cell_deg, clean(reference[3][r]));
  }

  finish_brush(result_, config_, total, profile, start_);
  BrushSummary& s = result_.summary;
  estimate_.lengths = static_cast<int>(lengths_.nodes.size());
  estimate_.diameters = static_cast<int>(diameters_.nodes.size());
  s.distinct_filaments = real_runs();
  s.population = estimate_;
  if (!reaching_.empty() && !estimate_.converged && !(options_.stop && options_.stop->stop_requested())) {
    char w[320];
    std::snprintf(w, sizeof w,
                  "the population's estimated error (mean normal force %.3g, hub torque %.3g, relative) is above "
                  "brush.population_tolerance = %.3g after %d representative filaments: raise "
                  "brush.population_max_runs, or use brush.method = \"filaments\"",
                  estimate_.normal_force_error, estimate_.hub_torque_error, estimate_.tolerance, real_runs());
    s.warnings.push_back(w);
  }
  int failed = 0;
  for (const Node& n : nodes_) failed += !n.zero && !n.orbit.state.ran;
  if (failed > 0)
    s.warnings.push_back(std::to_string(failed) + " representative filaments failed: the filaments whose values would "
                         "lean on them are counted failed and left out of the sums, as the filament route leaves out "
                         "a filament that fails (missing_force_fraction estimates their share)");
}

}  // namespace

BrushResult run_brush_population(const Config& config, const BrushOptions& options) {
  BrushResult result;
  Population(config, options, result).run();
  return result;
}

}  // namespace rotbeam::detail
