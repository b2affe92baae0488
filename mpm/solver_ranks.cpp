// A run spread over ranks. Each rank owns the points of the 2 x 2 x 2 block groups the partition
// gives it (partition.hpp). At the start of a step, points that crossed into another rank's group
// migrate there. Each rank scatters its own points; a block of nodes that groups of several ranks
// write (a shared block) gets, from each rank, its groups' sums per colour, and every rank holding
// it adds them in colour order (shared_blocks.hpp): the sum one rank forms, since a node's value
// is the colour-ordered sum of its groups' sums, each summed over its blocks by key and its points
// by (material, id) (particle_bins.hpp, group_sums.hpp). So every node a rank's points read holds
// the bits a run on one rank gives it, after each pass that adds (the scatter, the MUSL remap,
// the node average's sums),
// and the gathers, the stress update, motion and removal need no more than a rank's own points.
// The maxima and the exact sums are taken over ranks. The results are bitwise those of one rank,
// for any rank count.
#include <algorithm>
#include <array>
#include <bit>
#include <map>
#include <numeric>
#include <string>

#include <fmt/format.h>

#include "mpm/point_exchange.hpp"
#include "mpm/solver.hpp"

namespace hvi::mpm {

void Solver::distribute(Communicator* comm) {
  comm_ = comm;
  if (!distributed()) return;
  partition_ = Partition();
  shared_.combine = [this](int components, const SharedBlocks::Target& target) {
    combine_shared(shared_, grid_, components, target);
  };
  if (contact_)
    shared1_.combine = [this](int components, const SharedBlocks::Target& target) {
      combine_shared(shared1_, contact_->grid(), components, target);
    };
  for (auto* c : couplings_) c->spread(grid_ranks());
}

void Solver::add_coupling(GridCoupling* coupling) {
  if (distributed()) coupling->spread(grid_ranks());  // may refuse: then it is not added
  couplings_.push_back(coupling);
}

// A block belongs to the rank owning its group (the 2 x 2 x 2 blocks a group's points own); that
// rank's groups write it (writers_elsewhere), so it is always among the ranks holding it.
GridRanks Solver::grid_ranks() {
  return {comm_, [this](std::uint64_t block_key) {
            return partition_.rank_of(group_of_block(block_key));
          }};
}

// Each point to the rank owning its group. The partition is cut on the first step, and anew when
// the points per rank drift past 10% over the mean and a new cut would hold fewer on the fullest
// rank (a cut is only as even as its largest group allows).
void Solver::share_points() {
  auto t = timer_.scope("ranks: migrate points");
  const std::size_t n = particles_.size();
  std::vector<std::uint64_t> group;
  owner_block_keys(particles_, {settings_.shape, half_width_}, geometry_, group);
  for (auto& key : group) key = group_of_block(key);
  std::vector<std::uint64_t> keys = group;
  std::sort(keys.begin(), keys.end());
  std::vector<GroupLoad> mine;
  for (const auto k : keys)
    if (!mine.empty() && mine.back().key == k)
      ++mine.back().points;
    else
      mine.push_back({k, 1});
  const std::vector<GroupLoad> loads = global_loads(*comm_, mine);
  const bool first = partition_.ranks() != comm_->size();
  const auto now = points_per_rank(first ? Partition() : partition_, loads);
  if (first || needs_rebalance(now)) {
    Partition cut(loads, comm_->size());
    const double before = first ? 0.0 : imbalance(now);
    const double after = imbalance(points_per_rank(cut, loads));
    if (first || after < before) {
      partition_ = std::move(cut);
      sharing_.cuts += 1;
      sharing_.cut_step = state_.step;
      sharing_.imbalance_before = before;
      sharing_.imbalance_after = after;
    }
  }
  global_points_ = 0;
  for (const auto& g : loads) global_points_ += g.points;
  std::vector<int> destination(n);
  for (std::size_t p = 0; p < n; ++p) destination[p] = partition_.rank_of(group[p]);
  migrate(destination);
}

void Solver::count_points() {
  if (!distributed()) return;
  global_points_ = 0;
  for (const auto& count : comm_->all_gather({static_cast<double>(particles_.size())}))
    global_points_ += static_cast<std::size_t>(count.at(0));
}

void Solver::gather_to_root() {
  if (!distributed()) return;
  announce(Command::gather);
  auto t = timer_.scope("ranks: gather for output");
  migrate(std::vector<int>(particles_.size(), 0));
}

// Sends each point to its destination rank (its own stays), and regroups the arrays by material.
void Solver::migrate(const std::vector<int>& destination) {
  const int me = comm_->rank();
  std::vector<std::vector<std::uint32_t>> leaving(static_cast<std::size_t>(comm_->size()));
  std::vector<std::uint32_t> gone;  // ascending
  for (std::size_t p = 0; p < destination.size(); ++p)
    if (destination[p] != me) {
      leaving[static_cast<std::size_t>(destination[p])].push_back(static_cast<std::uint32_t>(p));
      gone.push_back(static_cast<std::uint32_t>(p));
    }
  std::vector<std::vector<double>> out(leaving.size());
  for (std::size_t r = 0; r < leaving.size(); ++r) out[r] = pack_points(particles_, leaving[r]);
  const auto in = exchange(std::move(out));
  std::vector<std::size_t> sizes;
  for (const auto& range : ranges_) sizes.push_back(range.size());
  particles_.erase(gone, sizes);
  for (std::size_t r = 0; r < in.size(); ++r)
    if (static_cast<int>(r) != me) append_points(particles_, in[r]);
  sharing_.migrated += static_cast<std::int64_t>(gone.size());
  group_by_material();
}

// A stable counting sort by material (the order inside a material does not change any sum).
void Solver::group_by_material() {
  std::vector<std::uint32_t> order(particles_.size());
  std::iota(order.begin(), order.end(), 0u);
  std::stable_sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
    return particles_.material[a] < particles_.material[b];
  });
  particles_.reorder(order);
  compute_material_ranges();
}

// Into `others`: the ranks but this one whose groups may write block `block_key`. Block x (on
// one axis) is written by the groups x / 2 and, for an even x, x / 2 - 1 (a group's points write
// its own blocks and the next one up, particle_bins.hpp). Called for every block every step: the
// caller's vector is reused.
void Solver::writers_elsewhere(std::uint64_t block_key, std::vector<int>& others) const {
  auto writers = [](int x) {
    return std::array<int, 2>{x % 2 == 0 && x > 0 ? x / 2 - 1 : x / 2, x / 2};
  };
  const auto c = SparseGrid::block_coords(block_key);
  const auto gx = writers(c[0]), gy = writers(c[1]), gz = writers(c[2]);
  others.clear();
  for (int z = gz[0]; z <= gz[1]; ++z)
    for (int y = gy[0]; y <= gy[1]; ++y)
      for (int x = gx[0]; x <= gx[1]; ++x) {
        const int r = partition_.rank_of(SparseGrid::block_key(x, y, z));
        if (r != comm_->rank() && std::find(others.begin(), others.end(), r) == others.end())
          others.push_back(r);
      }
}

// The keys of `grid`'s blocks that groups of other ranks may write too.
std::vector<std::uint64_t> Solver::blocks_shared_with_others(const SparseGrid& grid) const {
  std::vector<std::uint64_t> keys;
  std::vector<int> others;
  for (std::uint32_t b = 0; b < grid.block_count(); ++b) {
    writers_elsewhere(grid.key(b), others);
    if (!others.empty()) keys.push_back(grid.key(b));
  }
  return keys;
}

// The blocks of this step's `grid` that groups of other ranks write too, with those ranks.
void Solver::find_shared_blocks(const SparseGrid& grid, SharedBlocks& s) {
  auto t = timer_.scope("ranks: shared nodes");
  s.slot.assign(grid.block_count(), SparseGrid::none);
  s.block.clear();
  s.ranks.clear();
  std::vector<int> others;
  for (std::uint32_t b = 0; b < grid.block_count(); ++b) {
    writers_elsewhere(grid.key(b), others);
    if (others.empty()) continue;
    s.slot[b] = static_cast<std::uint32_t>(s.block.size());
    s.block.push_back(b);
    s.ranks.push_back(others);
  }
  sharing_.shared_blocks += static_cast<std::int64_t>(s.count());
}

// After a pass that added `components` values per node, with the shared blocks' sums kept apart
// per colour: sends each shared block's colours to the ranks sharing it, and sets its nodes in
// `target` to the colour-ordered sum of every rank's (shared_blocks.hpp). A message is, per block:
// its key, the mask of its colours, then 64 nodes x components per colour.
void Solver::combine_shared(SharedBlocks& s, const SparseGrid& grid, int components,
                            const SharedBlocks::Target& target) {
  auto t = timer_.scope("ranks: shared nodes");
  constexpr int colours = SharedBlocks::colours, S = SharedBlocks::S;
  const std::size_t per_colour = static_cast<std::size_t>(components) * S;
  std::vector<std::vector<double>> out(static_cast<std::size_t>(comm_->size()));
  for (std::size_t i = 0; i < s.count(); ++i) {
    unsigned mask = 0;
    for (int k = 0; k < colours; ++k)
      if (s.has_local[i * colours + static_cast<std::size_t>(k)]) mask |= 1u << k;
    if (mask == 0) continue;
    for (const int r : s.ranks[i]) {
      auto& o = out[static_cast<std::size_t>(r)];
      o.push_back(std::bit_cast<double>(grid.key(s.block[i])));
      o.push_back(static_cast<double>(mask));
      for (int k = 0; k < colours; ++k)
        if (mask & (1u << k)) {
          const double* sums =
              s.local.data() + (i * colours + static_cast<std::size_t>(k)) * per_colour;
          o.insert(o.end(), sums, sums + per_colour);
        }
    }
  }
  const auto in = exchange(std::move(out));
  for (const auto& from : in)
    for (std::size_t at = 0; at < from.size();) {
      const std::uint32_t b = grid.find(std::bit_cast<std::uint64_t>(from[at]));
      const auto mask = static_cast<unsigned>(from[at + 1]);
      at += 2;
      const std::uint32_t i = b == SparseGrid::none ? SparseGrid::none : s.slot[b];
      for (int k = 0; k < colours; ++k) {
        if (!(mask & (1u << k))) continue;
        if (i != SparseGrid::none) {
          const std::size_t to =
              static_cast<std::size_t>(i) * colours + static_cast<std::size_t>(k);
          std::copy_n(&from[at], per_colour, s.remote.data() + to * per_colour);
          s.has_remote[to] = 1;
        }
        at += per_colour;
      }
    }
  const auto count = static_cast<std::int64_t>(s.count());
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < count; ++i)
    for (int c = 0; c < components; ++c) {
      double* node = target(s.block[static_cast<std::size_t>(i)], c);
      for (int l = 0; l < S; ++l) {
        double sum = 0.0;  // ((0 + G^0) + G^1) + ..., each colour from the rank holding its group
        for (int k = 0; k < colours; ++k) {
          const std::size_t at =
              static_cast<std::size_t>(i) * colours + static_cast<std::size_t>(k);
          const std::size_t value =
              at * per_colour + static_cast<std::size_t>(c) * S + static_cast<std::size_t>(l);
          if (s.has_local[at])
            sum += s.local[value];
          else if (s.has_remote[at])
            sum += s.remote[value];
        }
        node[l] = sum;
      }
    }
}

// The friction heat of contact's last correction summed over the ranks as one rank sums it: each
// block's work once, exactly (exact_sum.hpp). A block only this rank holds counts here. A shared
// block may be held by several ranks, each with the same node values and so the same work: the
// ranks gather those by key and count each key once.
double Solver::contact_work_over_ranks(NodalVelocity which) const {
  if (which != NodalVelocity::end || !contact_->has_friction()) return 0.0;
  const std::vector<double>& work = contact_->block_work();
  std::array<ExactSum, 1> alone;
  std::vector<double> shared;  // (key, work) pairs
  for (std::uint32_t b = 0; b < work.size(); ++b) {
    if (work[b] == 0.0) continue;
    if (shared1_.slot[b] == SparseGrid::none) {
      alone[0] += work[b];
    } else {
      shared.push_back(std::bit_cast<double>(contact_->grid().key(b)));
      shared.push_back(work[b]);
    }
  }
  add_over_ranks(*comm_, alone);
  std::map<std::uint64_t, double> once;
  for (const auto& from : comm_->all_gather(shared))
    for (std::size_t k = 0; k + 1 < from.size(); k += 2)
      once.emplace(std::bit_cast<std::uint64_t>(from[k]), from[k + 1]);
  ExactSum total = alone[0];
  for (const auto& [key, w] : once) total += w;
  return total.value();
}

double Solver::agree_on_failure(const std::string& failure, double score, double x) const {
  if (!distributed()) {
    if (!failure.empty()) throw SolverError(failure);
    return x;
  }
  // (failed, score, x) of every rank; then, if any failed, every rank's message as characters.
  const auto flags = comm_->all_gather({failure.empty() ? 0.0 : 1.0, score, x});
  int chosen = -1;
  double largest = flags.at(0).at(2);
  for (std::size_t r = 0; r < flags.size(); ++r) {
    largest = std::max(largest, flags[r].at(2));
    if (flags[r].at(0) != 0.0 &&
        (chosen < 0 || flags[r].at(1) > flags[static_cast<std::size_t>(chosen)].at(1)))
      chosen = static_cast<int>(r);
  }
  if (chosen < 0) return largest;
  const auto messages = comm_->all_gather(std::vector<double>(failure.begin(), failure.end()));
  const auto& m = messages.at(static_cast<std::size_t>(chosen));
  std::string what;
  for (const double c : m) what.push_back(static_cast<char>(c));
  throw SolverError(what + (chosen == 0 ? "" : fmt::format(" (on rank {})", chosen)), true);
}

// Sends out[r] to rank r, counting the bytes that leave this rank.
std::vector<std::vector<double>> Solver::exchange(std::vector<std::vector<double>> out) {
  for (std::size_t r = 0; r < out.size(); ++r)
    if (static_cast<int>(r) != comm_->rank())
      sharing_.bytes_sent += static_cast<std::int64_t>(out[r].size() * sizeof(double));
  return comm_->exchange(std::move(out));
}

void Solver::announce(Command command, double argument) const {
  if (!leading_ || !distributed()) return;
  std::vector<double> message{static_cast<double>(command), argument};
  comm_->broadcast(message);
}

void Solver::gather_coupled_state() {
  if (!distributed()) return;
  announce(Command::coupled_state);
  for (auto* c : couplings_) c->gather_to_root();
}

void Solver::stop_followers(Communicator& comm) {
  std::vector<double> message{static_cast<double>(Command::stop), 0.0};
  comm.broadcast(message);
}

bool Solver::follow(const FollowerHooks& hooks) {
  bool failed = false;
  for (;;) {
    std::vector<double> message;
    comm_->broadcast(message);
    switch (static_cast<Command>(static_cast<int>(message.at(0)))) {
      case Command::stop:
        return failed;
      case Command::initialise:
        initialise();
        break;
      case Command::restore:
        hooks.restore();
        break;
      case Command::step:
        try {
          step(message.at(1));
        } catch (const SolverError& e) {
          if (!e.every_rank()) throw;
          failed = true;  // rank 0 reports it and leads what follows (the failure's snapshot)
        }
        break;
      case Command::energy:
        (void)energy();
        break;
      case Command::removal_events:
        (void)take_removal_events();
        break;
      case Command::gather:
        gather_to_root();
        break;
      case Command::pressure:
        (void)peak_pressure();
        break;
      case Command::write:
        hooks.write(message.at(1));
        break;
      case Command::positions:
        (void)positions_of({});
        break;
      case Command::measure:
        hooks.measure();
        break;
      case Command::grow:
        hooks.grow();
        break;
      case Command::coupled_state:
        gather_coupled_state();
        break;
    }
  }
}

std::vector<double> Solver::max_pairs_over_ranks(std::vector<double> pairs) const {
  if (!distributed()) return pairs;
  for (const auto& from : comm_->all_gather(pairs))
    for (std::size_t k = 0; k + 1 < std::min(from.size(), pairs.size()); k += 2)
      if (from[k] > pairs[k] || (from[k] == pairs[k] && from[k + 1] > pairs[k + 1])) {
        pairs[k] = from[k];
        pairs[k + 1] = from[k + 1];
      }
  return pairs;
}

std::vector<Solver::PointPosition> Solver::positions_of(std::vector<std::int64_t> ids) const {
  announce(Command::positions);
  if (distributed()) {  // rank 0's ids to every rank
    std::vector<double> message(ids.size());
    for (std::size_t k = 0; k < ids.size(); ++k) message[k] = std::bit_cast<double>(ids[k]);
    comm_->broadcast(message);
    ids.resize(message.size());
    for (std::size_t k = 0; k < ids.size(); ++k) ids[k] = std::bit_cast<std::int64_t>(message[k]);
  }
  std::sort(ids.begin(), ids.end());
  std::vector<double> mine;  // (id, x, y, z) of this rank's points among them
  const auto& P = particles_;
  for (std::size_t p = 0; p < P.size(); ++p)
    if (std::binary_search(ids.begin(), ids.end(), P.id[p])) {
      mine.push_back(std::bit_cast<double>(P.id[p]));
      mine.insert(mine.end(), &P.position[3 * p], &P.position[3 * p] + 3);
    }
  std::vector<PointPosition> found;
  const auto add = [&](const std::vector<double>& from) {
    for (std::size_t k = 0; k + 4 <= from.size(); k += 4)
      found.push_back(
          {std::bit_cast<std::int64_t>(from[k]), {from[k + 1], from[k + 2], from[k + 3]}});
  };
  if (distributed())
    for (const auto& from : comm_->all_gather(mine)) add(from);
  else
    add(mine);
  std::sort(found.begin(), found.end(),
            [](const PointPosition& a, const PointPosition& b) { return a.id < b.id; });
  return found;
}

// Every rank's removal events on every rank, listed by step, then id, as one rank lists them.
void Solver::gather_removal_events(std::vector<RemovalEvent>& events) const {
  constexpr std::size_t per = 12;
  std::vector<double> mine;
  mine.reserve(per * events.size());
  for (const auto& e : events) {
    for (const std::int64_t i : {e.id, e.body, e.material, e.step})
      mine.push_back(std::bit_cast<double>(i));
    mine.insert(mine.end(), e.position.begin(), e.position.end());
    mine.insert(mine.end(), e.velocity.begin(), e.velocity.end());
    mine.push_back(e.mass);
    mine.push_back(e.time);
  }
  events.clear();
  for (const auto& from : comm_->all_gather(mine))
    for (std::size_t k = 0; k + per <= from.size(); k += per) {
      const double* f = &from[k];
      RemovalEvent e{};
      e.id = std::bit_cast<std::int64_t>(f[0]);
      e.body = std::bit_cast<std::int64_t>(f[1]);
      e.material = std::bit_cast<std::int64_t>(f[2]);
      e.step = std::bit_cast<std::int64_t>(f[3]);
      for (int d = 0; d < 3; ++d) e.position[d] = f[4 + d], e.velocity[d] = f[7 + d];
      e.mass = f[10];
      e.time = f[11];
      events.push_back(e);
    }
  std::sort(events.begin(), events.end(), [](const RemovalEvent& a, const RemovalEvent& b) {
    return a.step != b.step ? a.step < b.step : a.id < b.id;
  });
}

}  // namespace hvi::mpm
