#include "ntn/hil/recorder.hpp"

#include <xxhash.h>

#include <array>
#include <bit>
#include <cstring>

namespace ntn::hil {

namespace {

static_assert(std::endian::native == std::endian::little,
              "the log is written in the host's byte order, which must be little-endian");

constexpr std::array<char, 8> kMagic = {'N', 'T', 'N', 'L', 'O', 'G', '1', '\0'};
constexpr std::uint32_t kVersion = 1;

template <class T>
void put(std::FILE* f, const T& v) {
  std::fwrite(&v, sizeof v, 1, f);
}

template <class T>
bool get(std::FILE* f, T& v) {
  return std::fread(&v, sizeof v, 1, f) == 1;
}

}  // namespace

std::uint64_t hash_outputs(std::span<const double> outputs) {
  return XXH3_64bits(outputs.data(), outputs.size_bytes());
}

Recorder::~Recorder() {
  (void)close();
}

bool Recorder::open(const std::string& path, const LogHeader& header) {
  file_ = std::fopen(path.c_str(), "wb");
  if (file_ == nullptr) {
    error_ = "cannot write " + path + ": " + std::strerror(errno);
    return false;
  }
  buffer_.resize(1 << 20);  // one allocation, before the run
  std::setvbuf(file_, buffer_.data(), _IOFBF, buffer_.size());
  std::fwrite(kMagic.data(), 1, kMagic.size(), file_);
  put(file_, kVersion);
  put(file_, header.inputs);
  put(file_, header.outputs);
  put(file_, header.substeps);
  put(file_, header.interpolate);
  put(file_, header.period);
  put(file_, header.dt);
  std::array<char, 64> name{};
  std::memcpy(name.data(), header.model.data(), std::min<std::size_t>(63, header.model.size()));
  std::fwrite(name.data(), 1, name.size(), file_);
  return true;
}

void Recorder::write_frame(std::int64_t frame, std::uint32_t input_flags,
                           std::uint32_t output_flags, std::span<const double> inputs,
                           std::span<const double> outputs) {
  if (file_ == nullptr) return;
  put(file_, frame);
  put(file_, input_flags);
  put(file_, output_flags);
  std::fwrite(inputs.data(), sizeof(double), inputs.size(), file_);
  std::fwrite(outputs.data(), sizeof(double), outputs.size(), file_);
  put(file_, hash_outputs(outputs));
}

bool Recorder::close() {
  if (file_ == nullptr) return true;
  const bool ok = std::fflush(file_) == 0 && std::ferror(file_) == 0;
  std::fclose(file_);
  file_ = nullptr;
  if (!ok) error_ = "write error in the log";
  return ok;
}

std::optional<Log> read_log(const std::string& path, std::string& error) {
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (f == nullptr) {
    error = "cannot open " + path + ": " + std::strerror(errno);
    return std::nullopt;
  }
  auto fail = [&](const std::string& what) {
    error = path + ": byte " + std::to_string(std::ftell(f)) + ": " + what;
    std::fclose(f);
    return std::nullopt;
  };
  Log log;
  std::array<char, 8> magic{};
  std::uint32_t version = 0;
  if (std::fread(magic.data(), 1, magic.size(), f) != magic.size() || magic != kMagic)
    return fail("not an ntn-rt log (bad magic)");
  if (!get(f, version) || version != kVersion)
    return fail("unsupported log version " + std::to_string(version));
  LogHeader& h = log.header;
  std::array<char, 64> name{};
  if (!get(f, h.inputs) || !get(f, h.outputs) || !get(f, h.substeps) || !get(f, h.interpolate) ||
      !get(f, h.period) || !get(f, h.dt) ||
      std::fread(name.data(), 1, name.size(), f) != name.size())
    return fail("truncated header");
  if (h.inputs > 4096 || h.outputs > 4096) return fail("implausible channel counts");
  name.back() = '\0';
  h.model = name.data();
  for (;;) {
    LogFrame fr;
    if (!get(f, fr.frame)) break;  // clean end
    fr.inputs.resize(h.inputs);
    fr.outputs.resize(h.outputs);
    if (!get(f, fr.input_flags) || !get(f, fr.output_flags) ||
        std::fread(fr.inputs.data(), sizeof(double), h.inputs, f) != h.inputs ||
        std::fread(fr.outputs.data(), sizeof(double), h.outputs, f) != h.outputs ||
        !get(f, fr.hash))
      return fail("truncated frame " + std::to_string(log.frames.size()));
    log.frames.push_back(std::move(fr));
  }
  std::fclose(f);
  return log;
}

}  // namespace ntn::hil
