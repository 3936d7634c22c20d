// The loop's input schedule in real time (DESIGN §8): when frame k is due, given the arrival of a
// sender's packets. The sender sends frame f at e + f period (e: its epoch); the loop runs frame
// k at e + k period + period / 2, half a period after packet k is expected, so that arrival
// jitter below half a period makes no packet late and none more than a frame early.
//
// How e is known (hil_sim/README.md, "The input schedule"):
//  - Anchor: the first input packet seen arriving (frame f, at t) gives e = t - f period, if its
//    frame is plausible: inside the run and at most InputGate::kFrameWindow frames from the
//    loop's current frame. Anything else never sets the schedule.
//  - Resync: when K (`resync_after`, default 8) or more of the last 2K packets of the stream were
//    dropped on the same side (too early, beyond the jitter buffer; or late) with a consistent
//    offset (their frame minus the loop's frame within kResyncSpread of the newest one's), and
//    they are more than all the other packets of those 2K together, the stream
//    and the schedule disagree, not the packets: e is re-anchored to those K or more packets,
//    e = min over them of (time seen - frame period). A packet is seen when the loop reads it,
//    at or after its arrival, so this is the latest epoch they allow: a packet that follows on
//    time arrives at least half a period before its frame's deadline (not late) and, as the
//    loop reads its socket once a frame, at most 1.5 periods before it (kept in the jitter
//    buffer). The packets of the stream are those the gate used (current or buffered) or
//    dropped as too early or late; corrupt ones, wrong counts, duplicates, frame ends and
//    frames out of the run or the window are not counted at all. Before any anchor (no packet
//    within the first wait) the same rule anchors the schedule: a late sender is still followed.
//    "K of the last 2K", not "K in a row": a slowly drifting sender with jitter misses its
//    frames now and then before it misses them all, and each packet used in between would
//    otherwise start the count again (with 100 us of jitter and 200 ppm of drift, K in a row
//    lost 3 % of a 10 s run).
// So one packet never moves the schedule, except the first; while half of the stream's packets
// (K of any 2K in a row) are used at their frames it does not move at all; and a
// first packet that was wrong (a burst after a stall, a stale packet) is corrected after K
// packets. Every resync is counted and flags its frame with flag::kResync.
//
// Times are integer ns (CLOCK_MONOTONIC, or synthetic in the tests); every product and sum is
// checked: frames x period must fit an int64 with room, and a time that would overflow leaves the
// schedule unchanged. No heap, no libm: real-time safe.
#pragma once

#include <array>
#include <cstdint>

#include "ntn/hil/gate.hpp"

namespace ntn::hil {

class SenderSchedule {
 public:
  static constexpr int kResyncAfter = 8;  // K: packets on one side, of the last 2K
  static constexpr int kMaxResyncAfter = 32;
  static constexpr int kResyncSpread = 1;  // frames: their frame - loop frame within this
  static constexpr std::int64_t kMaxSpan = std::int64_t{1} << 61;  // ns: frames x period bound

  // period_ns > 0, frames > 0 with frames x period_ns <= kMaxSpan, resync_after in
  // [1, kMaxResyncAfter] (0 turns resync off: the schedule is then the first packet's alone, as
  // in the rule without resync).
  SenderSchedule(std::int64_t period_ns, std::int64_t frames, int resync_after = kResyncAfter);
  bool valid() const { return valid_; }

  // The first packet: frame `frame` seen arriving at `arrival_ns` while the loop is at frame
  // `current`. False (nothing set) if the frame is not plausible, the time would overflow, or the
  // schedule is already anchored.
  bool anchor(std::int64_t frame, std::int64_t arrival_ns, std::int64_t current = 0);

  // Every offer's result while the loop is at frame `current`, read from the socket at `seen_ns`.
  // Returns true when this packet completed a resync (the epoch moved).
  bool observe(const OfferResult& r, std::int64_t current, std::int64_t seen_ns);

  bool anchored() const { return anchored_; }
  // Deadline of the loop's frame 0 (e + period / 2), or -1 before the anchor.
  std::int64_t epoch_ns() const { return anchored_ ? epoch_ + period_ns_ / 2 : -1; }
  // The sender's epoch e (time of its frame 0), valid once anchored.
  std::int64_t sender_epoch_ns() const { return epoch_; }
  std::int64_t anchor_frame() const { return anchor_frame_; }  // frame of the first anchor, or -1
  std::uint64_t resyncs() const { return resyncs_; }
  std::int64_t last_resync_frame() const { return last_resync_frame_; }  // loop frame, or -1
  // flag::kResync if a resync happened since the last call, else 0 (the loop ORs it into the
  // frame's flags).
  std::uint16_t take_flags() {
    const std::uint16_t f = flags_;
    flags_ = 0;
    return f;
  }

 private:
  bool plausible(std::int64_t frame, std::int64_t current) const;
  // t - frame x period, false if it would overflow (frame is in [0, frames_) here).
  bool epoch_of(std::int64_t frame, std::int64_t t, std::int64_t& e) const;

  std::int64_t period_ns_ = 1;
  std::int64_t frames_ = 1;
  int resync_after_ = kResyncAfter;
  bool valid_ = false;
  bool anchored_ = false;
  std::int64_t epoch_ = 0;
  std::int64_t anchor_frame_ = -1;
  std::uint64_t resyncs_ = 0;
  std::int64_t last_resync_frame_ = -1;
  std::uint16_t flags_ = 0;
  // The last 2K packets of the stream: side (+1 too early, -1 late, 0 used), frame - loop frame,
  // and seen - frame x period.
  struct Seen {
    std::int64_t lead = 0;
    std::int64_t epoch = 0;
    int side = 0;
  };
  std::array<Seen, 2 * kMaxResyncAfter> recent_{};
  int recent_count_ = 0;  // entries in use, up to 2K
  int recent_next_ = 0;   // where the next one goes
};

}  // namespace ntn::hil
