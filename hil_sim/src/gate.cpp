#include "ntn/hil/gate.hpp"

#include <algorithm>
#include <cmath>

namespace ntn::hil {
namespace {

std::uint64_t all_channels(int channels) {
  return channels >= 64 ? ~std::uint64_t{0} : (std::uint64_t{1} << channels) - 1;
}

}  // namespace

InputGate::InputGate(int channels) {
  if (channels < 0 || channels > kMaxChannels) {
    valid_ = false;
    channels = 0;
  }
  channels_ = channels;
  min_.fill(-std::numeric_limits<double>::infinity());
  max_.fill(std::numeric_limits<double>::infinity());
}

InputGate::InputGate(std::span<const ntn::InputSpec> inputs)
    : InputGate(static_cast<int>(inputs.size())) {
  if (!valid_) return;
  for (int c = 0; c < channels_; ++c) {
    const ntn::InputSpec& in = inputs[static_cast<std::size_t>(c)];
    if (!set_range(c, in.min, in.max)) valid_ = false;
  }
}

bool InputGate::set_range(int channel, double min, double max) {
  if (channel < 0 || channel >= channels_ || started_) return false;
  if (std::isnan(min) || std::isnan(max) || min > max) return false;
  const auto c = static_cast<std::size_t>(channel);
  min_[c] = min;
  max_[c] = max;
  last_good_[c] = std::clamp(0.0, min, max);
  return true;
}

bool InputGate::set_initial(int channel, double value) {
  if (channel < 0 || channel >= channels_ || started_) return false;
  const auto c = static_cast<std::size_t>(channel);
  if (!std::isfinite(value) || value < min_[c] || value > max_[c]) return false;
  last_good_[c] = value;
  return true;
}

bool InputGate::set_run_frames(std::int64_t frames) {
  if (frames <= 0) return false;
  run_frames_ = frames;
  return true;
}

bool InputGate::begin_frame(std::int64_t frame) {
  if (started_ && frame <= current_) return false;
  std::uint16_t carried = 0;
  if (in_frame_) carried = static_cast<std::uint16_t>(pending_flags_ | close_frame(current_));
  if (started_) {
    // Close the frames skipped over. Only frames up to current_ + kJitterFrames can have
    // buffered packets; further ones beyond the missing window are counted in one go.
    std::int64_t j = current_ + 1;
    while (j < frame) {
      if (j > current_ + kJitterFrames && frame - j > kMissingWindow) {
        const std::int64_t to = frame - kMissingWindow;
        counters_.missing += static_cast<std::uint64_t>(to - j);
        carried |= flag::kMissing;
        if (channels_ > 0) carried |= flag::kHeld;
        j = to;
        continue;
      }
      carried |= close_frame(j);
      ++j;
    }
  }
  started_ = true;
  in_frame_ = true;
  current_ = frame;
  pending_flags_ = carried;
  return true;
}

InputGate::SequenceCheck InputGate::check_sequence(std::uint32_t sequence) {
  constexpr std::uint32_t kMask = kSequenceWindow - 1;
  if (!any_sequence_) {
    any_sequence_ = true;
    rebase_sequence(sequence);
    return SequenceCheck::kNewest;
  }
  // Serial-number arithmetic (RFC 1982): the u32 sequence may wrap.
  const auto d = static_cast<std::int32_t>(sequence - highest_sequence_);
  if (d > 0) {
    if (d >= kSequenceWindow) {
      seen_.reset();
    } else {
      for (std::uint32_t i = 1; i <= static_cast<std::uint32_t>(d); ++i) {
        seen_.reset((highest_sequence_ + i) & kMask);
      }
    }
    highest_sequence_ = sequence;
    seen_.set(sequence & kMask);
    return SequenceCheck::kNewest;
  }
  if (d == 0) return SequenceCheck::kDuplicate;
  if (-static_cast<std::int64_t>(d) >= kSequenceWindow) return SequenceCheck::kTooOld;
  if (seen_.test(sequence & kMask)) return SequenceCheck::kDuplicate;
  seen_.set(sequence & kMask);
  return SequenceCheck::kOlder;
}

void InputGate::rebase_sequence(std::uint32_t sequence) {
  highest_sequence_ = sequence;
  seen_.reset();
  seen_.set(sequence & (kSequenceWindow - 1));
}

// The frame rules that do not depend on the sequence: inside the run, and within kFrameWindow of
// the current frame. Differences in unsigned arithmetic: any int64 frame may arrive.
bool InputGate::frame_in_run(std::int64_t frame, OfferResult& r) {
  if (frame < 0 || frame >= run_frames_) {
    ++counters_.out_of_run;
    pending_flags_ |= flag::kBadFrame;
    r.status = OfferStatus::kOutOfRun;
    return false;
  }
  const std::uint64_t distance =
      frame >= current_ ? static_cast<std::uint64_t>(frame) - static_cast<std::uint64_t>(current_)
                        : static_cast<std::uint64_t>(current_) - static_cast<std::uint64_t>(frame);
  if (distance > static_cast<std::uint64_t>(kFrameWindow)) {
    ++counters_.out_of_window;
    pending_flags_ |= flag::kBadFrame;
    r.status = OfferStatus::kOutOfWindow;
    return false;
  }
  return true;
}

OfferResult InputGate::offer(std::span<const std::byte> datagram) {
  OfferResult r;
  if (!in_frame_) return r;
  Packet p;
  r.error = decode(datagram, p);
  if (r.error == DecodeError::kOk && p.kind == PacketKind::kOutput) r.error = DecodeError::kKind;
  if (r.error != DecodeError::kOk) {
    ++counters_.corrupt;
    ++counters_.decode_errors[static_cast<std::size_t>(r.error)];
    pending_flags_ |= flag::kCorrupt;
    r.status = OfferStatus::kCorrupt;
    return r;
  }
  r.frame = p.frame;
  if (p.kind == PacketKind::kFrameEnd) {
    ++counters_.frame_ends;
    r.status = OfferStatus::kFrameEnd;
    return r;
  }
  if (p.count != channels_) {
    ++counters_.wrong_count;
    pending_flags_ |= flag::kWrongCount;
    r.status = OfferStatus::kWrongCount;
    return r;
  }
  if (!frame_in_run(p.frame, r)) return r;
  SequenceCheck s = check_sequence(p.sequence);
  // A sender restart: the sequence is not above the newest (a duplicate, older, or beyond the
  // window), yet the frame is newer than every frame seen. A resent copy keeps its frame and a
  // reordered packet has an older one, so neither can look like this; a sender that started
  // counting again from 0 (or anywhere) while its frames go on does.
  if (s != SequenceCheck::kNewest && p.frame > newest_frame_) {
    ++counters_.sender_restart;
    rebase_sequence(p.sequence);
    s = SequenceCheck::kNewest;
  }
  if (s != SequenceCheck::kDuplicate) newest_frame_ = std::max(newest_frame_, p.frame);
  if (s == SequenceCheck::kDuplicate) {
    ++counters_.duplicate;
    pending_flags_ |= flag::kDuplicate;
    r.status = OfferStatus::kDuplicate;
    return r;
  }
  if (s != SequenceCheck::kNewest) {
    ++counters_.reordered;
    pending_flags_ |= flag::kReordered;
  }
  return place(p.frame, p.channels());
}

OfferResult InputGate::accept_values(std::int64_t frame, std::span<const double> values) {
  OfferResult r;
  if (!in_frame_) return r;
  r.frame = frame;
  if (values.size() != static_cast<std::size_t>(channels_)) {
    ++counters_.wrong_count;
    pending_flags_ |= flag::kWrongCount;
    r.status = OfferStatus::kWrongCount;
    return r;
  }
  if (!frame_in_run(frame, r)) return r;
  return place(frame, values);
}

OfferResult InputGate::place(std::int64_t frame, std::span<const double> values) {
  OfferResult r;
  r.frame = frame;
  if (frame < current_) {
    ++counters_.late;
    pending_flags_ |= flag::kLate;
    const std::size_t bit = static_cast<std::size_t>(frame & (kMissingWindow - 1));
    // Differences of frame indices in unsigned arithmetic: any int64 frame may arrive (a fuzzer
    // sent INT64_MIN), and the true difference, though it may not fit int64, fits uint64.
    const std::uint64_t behind =
        static_cast<std::uint64_t>(current_) - static_cast<std::uint64_t>(frame);
    if (behind <= static_cast<std::uint64_t>(kMissingWindow) && missing_.test(bit)) {
      ++counters_.late_for_missing;
      missing_.reset(bit);
    }
    r.status = OfferStatus::kLate;
    return r;
  }
  const std::uint64_t ahead =
      static_cast<std::uint64_t>(frame) - static_cast<std::uint64_t>(current_);
  if (ahead > static_cast<std::uint64_t>(kJitterFrames)) {
    ++counters_.too_early;
    pending_flags_ |= flag::kTooEarly;
    r.status = OfferStatus::kTooEarly;
    return r;
  }
  Slot& s = slot(frame);
  if (s.frame == frame) {
    ++counters_.duplicate;
    pending_flags_ |= flag::kDuplicate;
    r.status = OfferStatus::kDuplicate;
    return r;
  }
  s.frame = frame;
  std::copy(values.begin(), values.end(), s.values.begin());
  if (frame > current_) {
    ++counters_.early;
    pending_flags_ |= flag::kEarly;
    r.status = OfferStatus::kBuffered;
    return r;
  }
  r.status = OfferStatus::kCurrent;
  return r;
}

std::uint16_t InputGate::close_frame(std::int64_t frame) {
  std::uint16_t f = 0;
  held_mask_ = 0;
  const std::size_t bit = static_cast<std::size_t>(frame & (kMissingWindow - 1));
  Slot& s = slot(frame);
  if (s.frame != frame) {
    ++counters_.missing;
    missing_.set(bit);
    f |= flag::kMissing;
    if (channels_ > 0) f |= flag::kHeld;
    held_mask_ = all_channels(channels_);
    return f;
  }
  ++counters_.accepted;
  missing_.reset(bit);
  for (std::size_t c = 0; c < static_cast<std::size_t>(channels_); ++c) {
    const double v = s.values[c];
    if (!std::isfinite(v)) {
      ++counters_.nonfinite;
      f |= flag::kNonFinite | flag::kHeld;
      held_mask_ |= std::uint64_t{1} << c;
    } else if (v < min_[c] || v > max_[c]) {
      ++counters_.out_of_range;
      f |= flag::kOutOfRange | flag::kHeld;
      held_mask_ |= std::uint64_t{1} << c;
    } else {
      last_good_[c] = v;
    }
  }
  s.frame = kNoFrame;
  return f;
}

void InputGate::end_frame(std::span<double> values_out, std::uint16_t& flags_out) {
  std::uint16_t f = 0;
  if (in_frame_) {
    f = static_cast<std::uint16_t>(pending_flags_ | close_frame(current_));
    pending_flags_ = 0;
    in_frame_ = false;
  }
  const std::size_t n = std::min(values_out.size(), static_cast<std::size_t>(channels_));
  std::copy_n(last_good_.begin(), n, values_out.begin());
  flags_out = f;
}

}  // namespace ntn::hil
