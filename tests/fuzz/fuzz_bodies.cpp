#include "fuzz_bodies.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <span>
#include <string>
#include <string_view>

#include "ntn/hil/gate.hpp"
#include "ntn/hil/packet.hpp"
#include "ntn/hil/schedule.hpp"
#include "ntn/modelc/emit_header.hpp"
#include "ntn/modelc/load_model.hpp"
#include "ntn/modelc/model_report.hpp"
#include "record.hpp"

namespace ntn_fuzz {

namespace {

// A broken invariant is a finding: abort so that libFuzzer keeps the input.
void require(bool ok) {
  if (!ok) std::abort();
}

std::string_view text(const std::uint8_t* data, std::size_t size) {
  return {reinterpret_cast<const char*>(data), size};
}

void check_record(const ntn::io::ReadResult& r) {
  require(r.record.has_value() != r.error.has_value());  // exactly one of the two
  if (r.record) {
    // The sample-interval rule: every record's duration and step count
    // are finite and bounded.
    require(r.record->dt >= ntn::io::kMinSampleInterval &&
            r.record->dt <= ntn::io::kMaxSampleInterval);
    require(std::isfinite(r.record->t0));
    for (double v : r.record->values)
      require(std::isfinite(v));
    (void)r.record->at(0.5 * r.record->duration());
    // A stated unit that parses is the one `unit` holds; conversion to a g input either refuses
    // or leaves finite values (item 16).
    require(!r.record->unit || ntn::io::parse_unit(r.record->units).has_value());
    ntn::io::Record copy = *r.record;
    if (!copy.to_unit(ntn::io::input_unit(true, 0, 9.80665))) {
      for (double v : copy.values)
        require(std::isfinite(v));
    }
  } else {
    (void)r.error->format();
  }
}

}  // namespace

void modelc(const std::uint8_t* data, std::size_t size) {
  const ntn::modelc::LoadResult r = ntn::modelc::load_model_from_string(text(data, size), "fuzz");
  require(r.ok() == r.errors.empty());  // a model exactly when there is no error
  // Every listed error is counted; the rest of the list are the cap's summary notes.
  require(
      static_cast<std::size_t>(std::count_if(r.errors.begin(), r.errors.end(), [](const auto& d) {
        return d.severity == ntn::modelc::Severity::kError;
      })) <= r.error_count);
  for (const auto& d : r.errors)
    (void)d.format();
  if (!r.ok()) return;
  // A model that loads can run (the kernel's frame rule), is described and compiles to a header
  // (emit_header throws on a non-finite number: the loader must have refused it).
  require(ntn::frame_substeps(r.model->settings.dt, r.model->settings.frame_period).ok());
  require(r.model->stable.dt_stable > 0 && std::isfinite(r.model->stable.dt_stable));
  (void)ntn::modelc::info_text(*r.model);
  (void)ntn::modelc::emit_header(*r.model);
}

void at2(const std::uint8_t* data, std::size_t size) {
  check_record(ntn::io::read_at2_text(text(data, size), "fuzz.AT2"));
}

void csv(const std::uint8_t* data, std::size_t size) {
  // Odd-sized inputs ask for a column by name: the header's last name, up to any '[' (so the
  // named-column path is taken, found or not); even-sized ones take the default column.
  const std::string_view all = text(data, size);
  std::string column;
  if (size % 2 == 1) {
    std::string_view head = all.substr(0, all.find_first_of("\r\n"));
    if (const auto comma = head.rfind(','); comma != std::string_view::npos)
      head = head.substr(comma + 1);
    head = head.substr(0, head.find('['));
    while (!head.empty() && (head.front() == ' ' || head.front() == '"'))
      head.remove_prefix(1);
    column = std::string(head);
  }
  check_record(ntn::io::read_csv_text(all, column, "fuzz.csv"));
}

namespace {

void packet_bytes(std::span<const std::byte> bytes) {
  const std::size_t size = bytes.size();

  // decode: only a datagram of exactly packet_size(count) with a good checksum decodes, and
  // re-encoding what it gave decodes to the same packet.
  ntn::hil::Packet p;
  const ntn::hil::DecodeError e = ntn::hil::decode(bytes, p);
  if (e == ntn::hil::DecodeError::kOk) {
    require(p.count <= ntn::hil::kMaxChannels && size == ntn::hil::packet_size(p.count));
    std::array<std::byte, ntn::hil::kMaxPacketBytes> out{};
    const std::size_t n = ntn::hil::encode(p, out);
    require(n == size);
    ntn::hil::Packet q;
    require(ntn::hil::decode(std::span<const std::byte>(out.data(), n), q) ==
            ntn::hil::DecodeError::kOk);
    require(q.kind == p.kind && q.frame == p.frame && q.sequence == p.sequence &&
            q.count == p.count && q.flags == p.flags);
  }
  (void)ntn::hil::to_string(e);
  ntn::hil::Packet typed;
  (void)ntn::hil::decode(bytes, typed, ntn::hil::PacketKind::kInput);

  // The input gate, 3 channels in [-1, 1], a run of kFrames frames: whatever is offered, what
  // comes out is finite and in range. The datagram is offered at frame 0 and again (a duplicate)
  // at the packet's own frame when that is close, so the early / current / late paths all see it.
  constexpr std::int64_t kFrames = 1000, kPeriod = 1'000'000, kArrival = 5'000'000'000;
  ntn::hil::InputGate gate(3);
  for (int c = 0; c < 3; ++c)
    require(gate.set_range(c, -1.0, 1.0));
  require(gate.set_run_frames(kFrames));
  std::array<double, 3> values{};
  std::uint16_t flags = 0;
  require(gate.begin_frame(0));
  const ntn::hil::OfferResult first = gate.offer(bytes);
  gate.end_frame(values, flags);

  // The sender schedule (schedule.hpp), as the real-time loop drives it: the packet as the first
  // one (the anchor), then K times as a resync candidate. Only a frame inside the run and the
  // window may fix the deadlines, and then the loop's frame 0 is due within the run's span of
  // the arrival: no overflow, no deadline days away (the regression: frame 18 445 744 073 710).
  ntn::hil::SenderSchedule schedule(kPeriod, kFrames);
  require(schedule.valid());
  using ntn::hil::OfferStatus;
  if (first.status == OfferStatus::kCurrent || first.status == OfferStatus::kBuffered ||
      first.status == OfferStatus::kTooEarly) {
    if (schedule.anchor(first.frame, kArrival, 0))
      require(first.frame >= 0 && first.frame < kFrames &&
              first.frame <= ntn::hil::InputGate::kFrameWindow);
  }
  for (int i = 0; i < ntn::hil::SenderSchedule::kResyncAfter; ++i)
    (void)schedule.observe(first, 0, kArrival + i * kPeriod);
  if (schedule.anchored()) {
    const std::int64_t epoch = schedule.epoch_ns();
    require(epoch >= kArrival - kFrames * kPeriod &&
            epoch <= kArrival + ntn::hil::SenderSchedule::kResyncAfter * kPeriod);
  } else {
    require(schedule.epoch_ns() == -1);
  }

  std::int64_t next = 1;
  if (first.status == ntn::hil::OfferStatus::kBuffered && first.frame > 0 && first.frame < 64)
    next = first.frame;
  require(gate.begin_frame(next));
  (void)gate.offer(bytes);
  gate.end_frame(values, flags);
  for (double v : values)
    require(std::isfinite(v) && v >= -1.0 && v <= 1.0);
}

}  // namespace

void packet(const std::uint8_t* data, std::size_t size) {
  const std::span<const std::byte> bytes(reinterpret_cast<const std::byte*>(data), size);
  packet_bytes(bytes);
  // The same bytes with a correct checksum in the last 8 bytes: random bytes almost never carry
  // a valid XXH3, so without this the fuzzer would rarely get past decode into the gate.
  if (size < ntn::hil::kChecksumBytes || size > ntn::hil::kReceiveBufferBytes) return;
  std::array<std::byte, ntn::hil::kReceiveBufferBytes> fixed{};
  std::copy(bytes.begin(), bytes.end(), fixed.begin());
  const std::size_t body = size - ntn::hil::kChecksumBytes;
  const std::uint64_t sum = ntn::hil::checksum(std::span<const std::byte>(fixed.data(), body));
  for (std::size_t i = 0; i < ntn::hil::kChecksumBytes; ++i)
    fixed[body + i] = static_cast<std::byte>((sum >> (8 * i)) & 0xFFU);
  packet_bytes(std::span<const std::byte>(fixed.data(), size));
}

}  // namespace ntn_fuzz
