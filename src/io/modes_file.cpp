#include "spp/io/modes_file.hpp"

#include "io/json.hpp"

namespace spp {

namespace {

io::json point_json(const modes::ModePoint& p) {
  return {{"energy", p.energy},
          {"frequency", p.frequency},
          {"period", p.period},
          {"impact_times", p.impact_times},
          {"x0", io::vector_json(p.x0)},
          {"v0", io::vector_json(p.v0)},
          {"admissible", p.admissible},
          {"margin", p.margin},
          {"multiplicity", p.multiplicity}};
}

}  // namespace

std::string modes_json(const System& system, const modes::ModesResult& result, int indent) {
  io::json j;
  j["system"] = io::embedded_system_to_json(system);  // as in solve's result files: w unit, with its input norm
  j["linear_frequencies"] = io::vector_json(result.linear_frequencies);
  j["status"] = modes::to_string(result.status);
  j["stats"] = {{"corrector_solves", result.corrector_solves},
                {"stalled_families", result.stalled_families},
                {"inadmissible_stretches", result.inadmissible_stretches},
                {"seconds", result.seconds}};
  io::json families = io::json::array();
  for (const modes::ModeFamily& f : result.families) {
    io::json points = io::json::array(), events = io::json::array();
    for (const modes::ModePoint& p : f.points) points.push_back(point_json(p));
    for (const modes::ModeEvent& e : f.events)
      events.push_back({{"kind", modes::to_string(e.kind)},
                        {"detail", e.detail},
                        {"energy", e.at.energy},
                        {"frequency", e.at.frequency},
                        {"period", e.at.period}});
    families.push_back({{"k", f.k},
                        {"label", f.label},
                        {"symmetry", modes::to_string(f.symmetry)},
                        {"mode", f.mode},
                        {"multiplicity", f.multiplicity},
                        {"points", points},
                        {"events", events}});
  }
  j["families"] = families;
  return j.dump(indent) + "\n";
}

}  // namespace spp
