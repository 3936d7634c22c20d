// Stage add_loads: each [[loads]] table's non-zero components as kernel loads on its node,
// scaled by its time function (or constant), with the table's place kept per kernel load.
#include "compile.hpp"

namespace ntn::modelc::compile {

void add_loads(Compilation& comp) {
  const SourceModel& p = comp.p;
  ModelDescription& d = comp.d;
  auto ref = [&comp](const std::map<std::string, int>& index, const IdAt& id,
                     const std::string& what) { return comp.ref(index, id, what); };
  for (const Load& l : p.loads) {
    const int n = comp.node_of(l.node, l.at);
    int f = kConstant;
    if (l.function) f = ref(comp.ids.functions, *l.function, "time function");
    if (n < 0 || (l.function && f < 0)) continue;
    for (const auto& [dof, value] : l.components) {
      d.loads.push_back({n, dof, value, f});
      comp.load_at.push_back(l.at);
    }
  }
}

}  // namespace ntn::modelc::compile
