#include "ntn/hil/loaded_model.hpp"

#include "ntn/modelc/memory.hpp"

#include <cstdio>
#include <new>
#include <string>
#include <utility>

namespace ntn::hil {

void LoadedModel::FreeBlock::operator()(std::byte* p) const {
  ::operator delete (p, std::align_val_t{kRunTimeBlockAlign});
}

LoadedModel::LoadedModel(modelc::ModelDescription description, const RunTimeOptions& options)
    : d_(std::move(description)),
      spec_(runtime_spec(d_.view())),
      parts_(std::make_unique<RunTimeParts>()),
      buffers_(d_.sizes()) {
  info_.name = d_.name;
  info_.source_file = d_.source_file;
  for (const std::string& n : d_.input_names)
    info_.input_names.emplace_back(n);
  for (const std::string& n : d_.output_names)
    info_.output_names.emplace_back(n);
  for (const std::string& n : d_.output_units)
    info_.output_units.emplace_back(n);
  for (const modelc::OutputAlarm& a : d_.output_alarms) {
    info_.alarm_limits.push_back(a.limit);
    info_.alarm_hysteresis.push_back(a.hysteresis);
  }
  for (const modelc::MemberInfo& m : d_.members)
    info_.member_names.emplace_back(m.name);
  for (const modelc::HingeInfo& h : d_.hinge_info)
    info_.hinge_names.emplace_back(h.name);
  const Sizes z = d_.sizes();
  bytes_ = runtime_block_bytes(z, options);
  // One block for every array, allocated here and only here.
  block_.reset(static_cast<std::byte*>(
      ::operator new (bytes_ > 0 ? bytes_ : 1, std::align_val_t{kRunTimeBlockAlign})));
  bound_ = runtime_bind(*parts_, z, options, std::span<std::byte>(block_.get(), bytes_));
}

InitStatus LoadedModel::init() {
  if (!bound_) return {InitError::kStorageSizes, -1};
  return ntn::init(spec_, parts_->model, parts_->init_work);
}

LoadedModel::~LoadedModel() = default;

std::optional<std::string> storage_memory_refusal(const modelc::ModelDescription& description,
                                                  const RunTimeOptions& options) {
  const Sizes z = description.sizes();
  return modelc::memory_refusal("the run-time storage", runtime_block_bytes(z, options),
                                std::to_string(z.elements) + " elements, " +
                                    std::to_string(z.nodes) + " nodes, " +
                                    std::to_string(z.hinges) + " hinges");
}

std::unique_ptr<LoadedModel> load_or_report(const std::string& path, const RunTimeOptions& options,
                                            const char* program, bool quiet, int& exit_code) {
  modelc::LoadResult r = modelc::load_model(path);
  if (!r.ok()) {
    std::fputs(modelc::format_all(r.errors).c_str(), stderr);
    exit_code = r.unreadable ? 2 : 1;  // unreadable: a usage error, no model to judge
    if (!r.unreadable)
      std::fprintf(stderr, "%s: %zu error%s in %s; nothing run\n", program, r.error_count,
                   r.error_count == 1 ? "" : "s", path.c_str());
    return nullptr;
  }
  if (!quiet) std::fputs(modelc::format_all(r.notes).c_str(), stderr);  // mechanisms
  if (const auto refused = storage_memory_refusal(*r.model, options)) {
    std::fprintf(stderr, "%s: error: %s\n", path.c_str(), refused->c_str());
    exit_code = 1;
    return nullptr;
  }
  exit_code = 0;
  return std::make_unique<LoadedModel>(std::move(*r.model), options);
}

}  // namespace ntn::hil
