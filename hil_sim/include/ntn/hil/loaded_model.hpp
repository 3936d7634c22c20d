// A model file loaded into run-time storage (kernel/include/ntn/runtime_storage.hpp): the model
// compiler's description (its arrays and the names the file gave) and one block, allocated once
// when the model is loaded and bound to the kernel's Model, State, Scratch and init workspace.
// init() builds the model in it; nothing is allocated after the constructor, in the step or in the
// loop (hil::LoopBuffers made here too). ntn-run, ntn-hil run and the Python module use it.
#pragma once

#include <cstddef>
#include <memory>
#include <optional>
#include <string>

#include "ntn/hil/loop.hpp"
#include "ntn/hil/model_info.hpp"
#include "ntn/modelc/load_model.hpp"
#include "ntn/runtime_storage.hpp"

namespace ntn::hil {

class LoadedModel {
 public:
  // Allocates and binds a block for the description's sizes (TeamWork and a second State as
  // `options` asks). The description must be one load_model() accepted. Then init().
  LoadedModel(modelc::ModelDescription description, const RunTimeOptions& options);
  LoadedModel(const LoadedModel&) = delete;
  LoadedModel& operator=(const LoadedModel&) = delete;
  ~LoadedModel();

  const modelc::ModelDescription& description() const { return d_; }
  const ModelSpec<kRunTime>& spec() const { return spec_; }
  const hil::ModelInfo& info() const { return info_; }  // names, views of description()
  // ntn::init() of the description into the storage (kStorageSizes if the binding failed).
  InitStatus init();
  bool bound() const { return bound_; }
  std::size_t block_bytes() const { return bytes_; }

  Model<kRunTime>& model() { return parts_->model; }
  const Model<kRunTime>& model() const { return parts_->model; }
  State<kRunTime>& state() { return parts_->state; }
  const State<kRunTime>& state() const { return parts_->state; }
  Scratch<kRunTime>& scratch() { return parts_->scratch; }
  InitWorkspace<kRunTime>& init_work() { return parts_->init_work; }
  TeamWork<kRunTime>& team_work() { return parts_->team_work; }
  State<kRunTime>& checkpoint() { return parts_->checkpoint; }
  hil::LoopBuffers<kRunTime>& loop_buffers() { return buffers_; }

 private:
  struct FreeBlock {
    void operator()(std::byte* p) const;
  };
  modelc::ModelDescription d_;
  ModelSpec<kRunTime> spec_;
  hil::ModelInfo info_;
  std::unique_ptr<RunTimeParts> parts_;
  std::unique_ptr<std::byte, FreeBlock> block_;
  std::size_t bytes_ = 0;
  hil::LoopBuffers<kRunTime> buffers_;
  bool bound_ = false;
};

// The message refusing a run-time block larger than the memory available (ntn::modelc::
// memory_refusal, with the block's exact size), or nullopt: asked before the constructor
// allocates it.
std::optional<std::string> storage_memory_refusal(const modelc::ModelDescription& description,
                                                  const RunTimeOptions& options);

// Loads a model file as ntn-run and ntn-hil do: its errors printed to stderr as
// file:line:column (its notes too, unless `quiet`), then "PROGRAM: N errors in FILE". nullptr
// and the exit code on failure (1: the model has errors, 2: the file cannot be read).
std::unique_ptr<LoadedModel> load_or_report(const std::string& path, const RunTimeOptions& options,
                                            const char* program, bool quiet, int& exit_code);

}  // namespace ntn::hil
