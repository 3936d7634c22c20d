// make_hostile_headers MODEL.toml OUTDIR: loads the model, puts each string of
// hostile_strings.hpp into every string the generated header carries (title, source file, input,
// output, unit, member and hinge names) and writes OUTDIR/hostile_<i>.hpp in namespace
// ntn::models::hostile_<i>. The names bypass the loader (which refuses control characters in
// names): this tests emit_header's own escaping, whatever it is given.
#include <cstdio>
#include <fstream>
#include <string>

#include "hostile_strings.hpp"
#include "ntn/modelc/emit_header.hpp"
#include "ntn/modelc/load_model.hpp"

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: make_hostile_headers MODEL.toml OUTDIR\n");
    return 2;
  }
  const auto r = ntn::modelc::load_model(argv[1]);
  if (!r.ok()) {
    std::fputs(ntn::modelc::format_all(r.errors).c_str(), stderr);
    return 1;
  }
  for (std::size_t i = 0; i < hostile::kCount; ++i) {
    const std::string s(hostile::kStrings[i]);
    ntn::modelc::ModelDescription m = *r.model;
    m.title = m.source_file = s;
    for (auto* names : {&m.input_names, &m.output_names, &m.output_units})
      for (std::string& n : *names)
        n = s;
    for (auto& member : m.members)
      member.name = s;
    for (auto& h : m.hinge_info)
      h.name = s;
    const std::string path = std::string(argv[2]) + "/hostile_" + std::to_string(i) + ".hpp";
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out << ntn::modelc::emit_header(m, "hostile_" + std::to_string(i));
    if (!out.flush()) {
      std::fprintf(stderr, "cannot write %s\n", path.c_str());
      return 1;
    }
  }
  return 0;
}
