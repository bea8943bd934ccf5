#include "search/pole_pairing.hpp"

#include <algorithm>
#include <map>

namespace spp::search {

// Each segment of a pole line between two crossings with lines of the other phase is paired in order. A curve may
// also pass through the tiny square where a vertical and a horizontal line cross, leaving the cell below right
// through its left or top edge and entering the cell above left through its bottom or right edge (seen: diagonally,
// and straight up inside the vertical strip). It shows as one extra exit at an end of one segment next to the
// crossing and one extra entry at an end of another: those are paired, per crossing. Anything else that does not
// pair is counted as unpaired.
void pair_across_pole_lines(PoleHits& hits, const AxisPlan& a1, const AxisPlan& a2, SolveStats& stats,
                            std::vector<UncertifiedRegion>& uncertified, std::vector<Candidate>& candidates) {
  auto pair = [&](const EdgeHit& from, const EdgeHit& to) {
    ++stats.strip_pairs;
    double g2 = to.g;
    if (from.b.dot(to.b) < 0) g2 = -g2;
    if ((from.g > 0) != (g2 > 0))
      candidates.push_back({0.5 * (from.t1 + to.t1), 0.5 * (from.t2 + to.t2), false, true, {}});
  };
  auto pair_in_order = [&](const std::vector<EdgeHit>& from, const std::vector<EdgeHit>& to) {
    for (size_t i = 0; i < std::min(from.size(), to.size()); ++i) pair(from[i], to[i]);
  };
  const size_t I = a1.cells(), J = a2.cells();
  // per crossing (vertical line, horizontal line): extra exits and extra entries of its four segment ends
  std::map<std::pair<size_t, size_t>, std::pair<std::vector<EdgeHit>, std::vector<EdgeHit>>> passes;
  auto unpaired = [&](long count, double t1, double t2) {
    stats.unpaired_crossings += count;
    uncertified.push_back({t1, t1, t2, t2, "pairing"});
  };
  auto sort_segment = [](std::vector<EdgeHit>& from, std::vector<EdgeHit>& to) {
    auto by_pos = [](const EdgeHit& x, const EdgeHit& y) { return x.pos < y.pos; };
    std::sort(from.begin(), from.end(), by_pos);
    std::sort(to.begin(), to.end(), by_pos);
  };
  // What is left of a segment once its diagonal passes are set apart pairs in order, or not at all.
  auto pair_segment = [&](const std::vector<EdgeHit>& from, const std::vector<EdgeHit>& to, double t1, double t2) {
    if (from.size() == to.size())
      pair_in_order(from, to);
    else
      unpaired(static_cast<long>(std::max(from.size(), to.size()) - std::min(from.size(), to.size())), t1, t2);
  };
  for (size_t i = 1; i < I; ++i) {  // vertical lines, segment j between horizontal lines j and j + 1
    if (!a1.pole[i]) continue;
    for (size_t j = 0; j < J; ++j) {
      auto& from = hits.v_from[i][j];
      auto& to = hits.v_to[i][j];
      sort_segment(from, to);
      if (from.size() == to.size() + 1 && j + 1 < J && a2.pole[j + 1]) {
        passes[{i, j + 1}].first.push_back(from.back());
        from.pop_back();
      } else if (to.size() == from.size() + 1 && j > 0 && a2.pole[j]) {
        passes[{i, j}].second.push_back(to.front());
        to.erase(to.begin());
      }
      pair_segment(from, to, a1.bp[i], a2.bp[j]);
    }
  }
  for (size_t j = 1; j < J; ++j) {  // horizontal lines, segment i between vertical lines i and i + 1
    if (!a2.pole[j]) continue;
    for (size_t i = 0; i < I; ++i) {
      auto& from = hits.h_from[j][i];
      auto& to = hits.h_to[j][i];
      sort_segment(from, to);
      if (from.size() == to.size() + 1 && i > 0 && a1.pole[i]) {
        passes[{i, j}].first.push_back(from.front());
        from.erase(from.begin());
      } else if (to.size() == from.size() + 1 && i + 1 < I && a1.pole[i + 1]) {
        passes[{i + 1, j}].second.push_back(to.back());
        to.pop_back();
      }
      pair_segment(from, to, a1.bp[i], a2.bp[j]);
    }
  }
  // Passes through a crossing: each leaves one segment with an extra exit (the top of a vertical segment below the
  // crossing, or the left end of a horizontal segment right of it) and enters another with an extra entry (the
  // bottom of the vertical segment above, or the right end of the horizontal segment left of it), in any of the four
  // combinations. One pass per crossing is paired; several at the same crossing are counted as unpaired.
  for (auto& [key, p] : passes) {
    if (p.first.size() == 1 && p.second.size() == 1)
      pair(p.first[0], p.second[0]);
    else
      unpaired(static_cast<long>(std::max(p.first.size(), p.second.size())), a1.bp[key.first], a2.bp[key.second]);
  }
}

}  // namespace spp::search
