// The input gate (DESIGN §8: bad input never reaches the state). Every datagram the loop
// receives goes through it; what comes out for a frame is one finite, in-range value per input
// channel, with flags saying what happened. Fixed-size storage: no allocation, ever.
//
// Per frame k the loop calls
//     gate.begin_frame(k);
//     for each datagram received since the last frame: gate.offer(bytes);   // UDP source
//       or gate.accept_values(k, values);                                   // file source
//     gate.end_frame(values_out, flags_out);
//
// Per input packet, in this order (a packet is counted once, under the first rule it meets):
//   corrupt      decode error of any kind (also an output packet sent to the gate)   -> dropped
//   wrong_count  channel count != channels()                                         -> dropped
//   out_of_run   frame < 0 or frame >= the run's frame count (set_run_frames)        -> dropped
//   out_of_window |frame - k| > kFrameWindow: not a plausible frame of this stream   -> dropped
//   (sender_restart: a sequence at or below the newest seen, on a packet whose frame is newer
//                than every frame seen: the sender restarted its sequence numbers; the
//                sequence window is re-based on it and the packet goes on as the newest)
//   duplicate    sequence seen before (window of kSequenceWindow), or a second
//                packet for a frame that already has one                             -> dropped
//   late         frame < k: its frame has been processed                             -> dropped
//   too_early    frame > k + kJitterFrames                                           -> dropped
//   early        k < frame <= k + kJitterFrames: kept, used at its frame
//   (current)    frame == k: used at end_frame
// and, besides, `reordered` counts packets whose sequence is below the highest seen (not
// duplicates). At end_frame(k): no packet for k -> `missing`, every channel holds its last good
// value; a packet for k -> `accepted`, and each value that is NaN/Inf (`nonfinite`) or outside
// the channel's [min, max] (`out_of_range`) holds the channel's last good value instead.
// A missing frame whose packet arrives later is counted `late` too (and `late_for_missing`), so
// the packets that never came are lost() = missing - late_for_missing.
// The frame checks come before the sequence checks, so a packet with an absurd frame index
// changes nothing: neither the sequence window nor (schedule.hpp) the deadlines.
#pragma once

#include <array>
#include <bitset>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>

#include "ntn/hil/packet.hpp"
#include "ntn/model_spec.hpp"

namespace ntn::hil {

struct GateCounters {
  std::uint64_t accepted = 0;          // packets used at their frame
  std::uint64_t corrupt = 0;           // datagrams that failed decode (see decode_errors)
  std::uint64_t wrong_count = 0;       // packets with a channel count != channels()
  std::uint64_t duplicate = 0;         // packets dropped as seen before / second for a frame
  std::uint64_t late = 0;              // packets for an already processed frame
  std::uint64_t late_for_missing = 0;  // of those, the first packet for a frame counted missing
  std::uint64_t early = 0;             // packets buffered for a later frame
  std::uint64_t too_early = 0;         // packets beyond the jitter buffer, dropped
  std::uint64_t reordered = 0;         // packets with a sequence below the highest seen
  std::uint64_t missing = 0;           // frames without a packet at end_frame (all held)
  std::uint64_t nonfinite = 0;         // values NaN or +-Inf (held)
  std::uint64_t out_of_range = 0;      // values outside [min, max] (held)
  std::uint64_t frame_ends = 0;        // lock-step frame-end markers seen (not a fault)
  std::uint64_t out_of_run = 0;        // packets for a frame < 0 or >= the run's frames
  std::uint64_t out_of_window = 0;     // packets more than kFrameWindow frames from the current
  std::uint64_t sender_restart = 0;    // sequence restarts recognised (packets not dropped)
  std::array<std::uint64_t, kDecodeErrorKinds> decode_errors{};  // corrupt, by DecodeError

  // Frames whose packet never arrived at all.
  std::uint64_t lost() const { return missing - late_for_missing; }
};

enum class OfferStatus : std::uint8_t {
  kCurrent,      // for the current frame: will be used at end_frame
  kBuffered,     // for a later frame within the jitter buffer (counted early)
  kFrameEnd,     // a lock-step frame-end marker for OfferResult::frame (not counted as input)
  kCorrupt,      // see OfferResult::error
  kWrongCount,   //
  kDuplicate,    //
  kLate,         //
  kTooEarly,     //
  kOutOfRun,     // frame < 0 or >= the run's frame count
  kOutOfWindow,  // frame more than kFrameWindow from the current frame
  kNotInFrame,   // offered outside begin_frame / end_frame: ignored, not counted
};

struct OfferResult {
  OfferStatus status = OfferStatus::kNotInFrame;
  std::int64_t frame = 0;                // the packet's frame, when it decoded
  DecodeError error = DecodeError::kOk;  // why it was corrupt
};

class InputGate {
 public:
  static constexpr int kJitterFrames = 8;       // packets for frames k+1..k+8 are kept
  static constexpr int kSequenceWindow = 1024;  // duplicate detection reach, in sequences
  static constexpr int kMissingWindow = 1024;   // late_for_missing reach, in frames
  // Plausibility: a packet more than this many frames before or after the current frame is not
  // a late or early packet of this stream but a stray or broken one (out_of_window).
  static constexpr int kFrameWindow = kMissingWindow;

  // `channels` (0..kMaxChannels) inputs, any finite value accepted, held values start at 0.
  explicit InputGate(int channels = 0);
  // One channel per InputSpec, range [min, max] (raw units, before scale); held values start at
  // 0, or at the nearer end of the range if 0 is outside it.
  explicit InputGate(std::span<const ntn::InputSpec> inputs);

  // False if the constructor got more than kMaxChannels (or negative) channels; the gate then
  // has 0 channels and every input packet is wrong_count.
  bool valid() const { return valid_; }
  int channels() const { return channels_; }

  // Configuration, before the first frame. False (and no change) for a bad channel, min > max,
  // a NaN bound, or an initial value that is not finite and in range.
  bool set_range(int channel, double min, double max);
  bool set_initial(int channel, double value);
  // The run's frame count: packets for frames >= frames (or < 0, always) are out_of_run.
  // Default: no upper bound. False (no change) for frames <= 0.
  bool set_run_frames(std::int64_t frames);
  std::int64_t run_frames() const { return run_frames_; }

  // Starts frame k. Frames must increase: false (and nothing done) if k <= the last frame.
  // Frames skipped over (k > last + 1), and a frame begun but not ended, are closed first as
  // end_frame would close them (buffered packets used, else missing); their flags are OR-ed into
  // frame k's. The first call fixes where the run starts (no frame before it is missing).
  bool begin_frame(std::int64_t frame);
  // One received datagram (any bytes; decode happens here).
  OfferResult offer(std::span<const std::byte> datagram);
  // Values from a file or other trusted-framing source for `frame`: the packet rules above
  // without decode and sequence checks (count, late / early / duplicate frame, NaN, range).
  OfferResult accept_values(std::int64_t frame, std::span<const double> values);
  // Ends the current frame: writes channels() values (last good, never NaN/Inf/out of range)
  // into values_out (which must hold at least channels()) and the frame's flag:: bits. Outside a
  // frame it only writes the held values, with flags 0.
  void end_frame(std::span<double> values_out, std::uint16_t& flags_out);

  const GateCounters& counters() const { return counters_; }
  std::uint64_t held_channels() const { return held_mask_; }  // bit c: channel c held, last frame
  bool in_frame() const { return in_frame_; }
  std::int64_t current_frame() const { return current_; }  // the frame begun last
  std::span<const double> last_good() const {
    return {last_good_.data(), static_cast<std::size_t>(channels_)};
  }

 private:
  static constexpr int kSlots = 16;  // > kJitterFrames + 1, power of two
  static_assert(kSlots > kJitterFrames + 1 && (kSlots & (kSlots - 1)) == 0);
  static constexpr std::int64_t kNoFrame = std::numeric_limits<std::int64_t>::min();

  struct Slot {
    std::int64_t frame = kNoFrame;
    std::array<double, kMaxChannels> values{};
  };
  enum class SequenceCheck : std::uint8_t { kNewest, kOlder, kTooOld, kDuplicate };

  Slot& slot(std::int64_t frame) { return slots_[static_cast<std::size_t>(frame & (kSlots - 1))]; }
  SequenceCheck check_sequence(std::uint32_t sequence);
  void rebase_sequence(std::uint32_t sequence);
  bool frame_in_run(std::int64_t frame, OfferResult& r);  // else counts it, sets r.status
  OfferResult place(std::int64_t frame, std::span<const double> values);
  std::uint16_t close_frame(std::int64_t frame);  // the end_frame bookkeeping, returns flags

  int channels_ = 0;
  bool valid_ = true;
  std::array<double, kMaxChannels> min_{};
  std::array<double, kMaxChannels> max_{};
  std::array<double, kMaxChannels> last_good_{};
  std::array<Slot, kSlots> slots_{};

  bool started_ = false;
  bool in_frame_ = false;
  std::int64_t current_ = 0;  // frame begun last
  std::uint16_t pending_flags_ = 0;
  std::uint64_t held_mask_ = 0;

  std::int64_t run_frames_ = std::numeric_limits<std::int64_t>::max();
  bool any_sequence_ = false;
  std::int64_t newest_frame_ = 0;  // largest frame of a packet past the sequence check
  std::uint32_t highest_sequence_ = 0;
  std::bitset<kSequenceWindow> seen_;    // bit s % window: sequence s seen (within the window)
  std::bitset<kMissingWindow> missing_;  // bit f % window: frame f was missing (not yet late)

  GateCounters counters_{};
};

}  // namespace ntn::hil
