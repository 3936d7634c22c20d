// Stage resolve_ids: an index per kind of id (materials, sections, members, time functions,
// inputs, outputs, curves, hinges, nodes) with every duplicate reported; time functions and
// curves concatenated into the description; gravity_function resolved.
#include "compile.hpp"

namespace ntn::modelc::compile {
namespace {

// Index by id; reports every repeat at the repeated id, naming the line of the first.
template <class T, class GetId>
std::map<std::string, int> index_by_id(DiagnosticSink& L, const std::vector<T>& items, GetId get,
                                       const std::string& what) {
  std::map<std::string, int> index;
  for (std::size_t i = 0; i < items.size(); ++i) {
    const IdAt& id = get(items[i]);
    const auto [it, inserted] = index.emplace(id.id, static_cast<int>(i));
    if (!inserted) {
      const IdAt& first = get(items[static_cast<std::size_t>(it->second)]);
      L.error(id.at, "duplicate " + what + " '" + id.id + "' (first defined at line " +
                         std::to_string(first.at.line) + ")");
    }
  }
  return index;
}
}  // namespace

void resolve_ids(Compilation& comp) {
  DiagnosticSink& L = comp.L;
  const SourceModel& p = comp.p;
  ModelDescription& d = comp.d;
  Settings& s = comp.d.settings;
  auto ref = [&comp](const std::map<std::string, int>& index, const IdAt& id,
                     const std::string& what) { return comp.ref(index, id, what); };
  comp.ids.materials = index_by_id(
      L, p.materials, [](const Material& m) -> const IdAt& { return m.id; }, "material id");
  comp.ids.sections = index_by_id(
      L, p.sections, [](const Section& x) -> const IdAt& { return x.id; }, "section id");
  comp.ids.members = index_by_id(
      L, p.members, [](const Member& x) -> const IdAt& { return x.id; }, "member id");
  comp.ids.functions = index_by_id(
      L, p.time_functions, [](const TimeFunction& x) -> const IdAt& { return x.id; },
      "time function id");
  index_by_id(
      L, p.inputs, [](const Input& x) -> const IdAt& { return x.name; }, "input name");
  index_by_id(
      L, p.outputs, [](const Output& x) -> const IdAt& { return x.name; }, "output name");
  comp.ids.curves = index_by_id(
      L, p.curves, [](const Curve& x) -> const IdAt& { return x.id; }, "curve id");
  comp.ids.hinge_ids = index_by_id(
      L, p.hinges, [](const HingeIn& x) -> const IdAt& { return x.id; }, "hinge id");
  std::map<long long, int>& node_index = comp.ids.nodes;
  for (std::size_t i = 0; i < p.nodes.size(); ++i) {
    const UserNode& n = p.nodes[i];
    const auto [it, inserted] = node_index.emplace(n.id, static_cast<int>(i));
    if (!inserted) {
      L.error(n.at, "duplicate node id " + std::to_string(n.id) + " (first defined at line " +
                        std::to_string(p.nodes[static_cast<std::size_t>(it->second)].at.line) +
                        ")");
    }
  }

  // Time functions, concatenated.
  for (const TimeFunction& f : p.time_functions) {
    d.time_functions.push_back(
        {static_cast<int>(d.time_points.size()), static_cast<int>(f.points.size())});
    d.time_points.insert(d.time_points.end(), f.points.begin(), f.points.end());
    d.time_function_ids.push_back(f.id.id);
  }
  if (p.model.gravity_function) {
    s.gravity_function = ref(comp.ids.functions, *p.model.gravity_function, "time function");
  }

  // Force-deformation curves, concatenated like time functions.
  for (const Curve& c : p.curves) {
    d.curves.push_back(
        {static_cast<int>(d.curve_points.size()), static_cast<int>(c.points.size())});
    d.curve_points.insert(d.curve_points.end(), c.points.begin(), c.points.end());
    d.curve_ids.push_back(c.id.id);
  }
}

}  // namespace ntn::modelc::compile
