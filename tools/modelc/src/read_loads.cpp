// The reader's tables of the loads: time functions, nodal loads and member loads
// (read_tables.hpp).
#include "read_tables.hpp"

#include <optional>
#include <string>

namespace ntn::modelc::compile {

// One [[time_functions]] table: id and its [t, value] points.
void read_time_function(Reader& L, const toml::table& tt, const std::string& path, SourceModel& p) {
  Table t(L, tt, path, {"id", "points"});
  t.check_unknown();
  auto id = read_id(L, t, "id");
  const auto points = read_points(L, t, 1, "[t, value] points (at least one)", "t", " s", "times");
  if (!id || !points) return;
  TimeFunction f;
  for (const auto& [time, value] : *points)
    f.points.push_back({time, value});
  f.id = *id;
  p.time_functions.push_back(f);
}

// One [[loads]] table: the node, dof and value or the force vector, and the time function.
void read_load(Reader& L, const toml::table& tt, const std::string& path, SourceModel& p) {
  Table t(L, tt, path, {"node", "dof", "value", "force", "function"});
  t.check_unknown();
  Load l;
  auto node = read_node_ref(L, t, "node", Need::kRequired);
  bool ok = node.has_value();
  if (t.conflict("dof", "force") || t.conflict("value", "force")) return;
  if (t.has("force")) {
    auto f = t.numbers("force", Need::kRequired, 6);
    if (f) {
      for (int d = 0; d < kDofsPerNode; ++d) {
        const double v = (*f)[static_cast<std::size_t>(d)];
        if (v != 0.0) l.components.emplace_back(d, v);
      }
    }
    ok = ok && f;
  } else {
    const std::string hint = " (or give force = [Fx, Fy, Fz, Mx, My, Mz])";
    const toml::node* dn = t.get("dof", Need::kRequired, hint);
    std::optional<int> dof;
    if (dn != nullptr) dof = L.choice(*dn, t.key("dof"), kDofNames);
    auto v = t.number("value", Need::kRequired);
    if (dof && v) l.components.emplace_back(*dof, *v);
    ok = ok && dof && v;
  }
  if (t.has("function")) {
    l.function = read_id(L, t, "function");
    ok = ok && l.function;
  }
  if (!ok) return;
  l.node = *node, l.at = t.where("node");
  p.loads.push_back(l);
}

// One [[member_loads]] table: the member, q or q_start + q_end, axes, the part (from / to or
// from_m / to_m) and the time function. Ranges in metres need the member's length: checked by
// add_member_loads.
void read_member_load(Reader& L, const toml::table& tt, const std::string& path, SourceModel& p) {
  Table t(L, tt, path,
          {"member", "q", "q_start", "q_end", "axes", "from", "to", "from_m", "to_m", "function"});
  t.check_unknown();
  MemberLoad ml;
  auto member = read_id(L, t, "member");
  bool ok = member.has_value();
  if (t.conflict("q", "q_start") || t.conflict("q", "q_end")) return;
  if (t.has("q")) {
    auto q = t.numbers("q", Need::kRequired, 3);
    if (q) ml.q_start = ml.q_end = {(*q)[0], (*q)[1], (*q)[2]};
    ok = ok && q;
  } else if (t.has("q_start") || t.has("q_end")) {
    const std::string hint = " (a linearly varying load needs both q_start and q_end)";
    std::optional<std::vector<double>> qs, qe;
    for (const std::string_view k : {"q_start", "q_end"}) {
      auto& q = k == "q_start" ? qs : qe;
      if (t.has(k)) {
        q = t.numbers(k, Need::kRequired, 3);
      } else {
        t.get(k, Need::kRequired, hint);
      }
    }
    if (qs) ml.q_start = {(*qs)[0], (*qs)[1], (*qs)[2]};
    if (qe) ml.q_end = {(*qe)[0], (*qe)[1], (*qe)[2]};
    ok = ok && qs && qe;
  } else {
    t.get("q", Need::kRequired, " (or q_start and q_end for a linearly varying load)");
    ok = false;
  }
  if (auto ax = t.choice("axes", Need::kOptional, {"global", "member"})) {
    ml.member_axes = *ax == 1;
  } else if (t.has("axes")) {
    ok = false;
  }
  // Fractions or metres, not both.
  for (const std::string_view f : {"from", "to"}) {
    for (const std::string_view m : {"from_m", "to_m"}) {
      if (t.conflict(f, m)) return;
    }
  }
  ml.in_metres = t.has("from_m") || t.has("to_m");
  const std::string_view kf = ml.in_metres ? "from_m" : "from";
  const std::string_view kt = ml.in_metres ? "to_m" : "to";
  ml.from_at = t.where(kf), ml.to_at = t.where(kt);
  const auto from = t.number(kf, Need::kOptional);
  const auto to = t.number(kt, Need::kOptional);
  ok = ok && (from || !t.has(kf)) && (to || !t.has(kt));
  if (from) ml.from = *from;
  if (to) ml.to = *to;
  if (ml.in_metres && !to) ml.to = -1;  // the member's end: set by add_member_loads
  if (from && !(ml.in_metres ? *from >= 0 : *from >= 0 && *from <= 1)) {
    L.error(ml.from_at, ml.in_metres
                            ? "must be between 0 and the member's length (got " + num(*from) + " m)"
                            : "must be between 0 and 1 (a fraction of the member's "
                              "length; got " +
                                  num(*from) + ")");
    ok = false;
  } else if (to && !(ml.in_metres ? *to >= 0 : *to >= 0 && *to <= 1)) {
    L.error(ml.to_at, ml.in_metres
                          ? "must be between 0 and the member's length (got " + num(*to) + " m)"
                          : "must be between 0 and 1 (a fraction of the member's "
                            "length; got " +
                                num(*to) + ")");
    ok = false;
  } else if (ok && (to || !ml.in_metres) && !(ml.from < ml.to)) {
    L.error(t.has(kt) ? ml.to_at : ml.from_at, std::string(kf) + " = " + num(ml.from) +
                                                   " must be less than " + std::string(kt) + " = " +
                                                   num(ml.to) + "");
    ok = false;
  }
  if (t.has("function")) {
    ml.function = read_id(L, t, "function");
    ok = ok && ml.function;
  }
  if (!ok) return;
  ml.member = *member;
  ml.at = t.where("member");
  p.member_loads.push_back(ml);
}

}  // namespace ntn::modelc::compile
