// The input gate (hil_sim/include/ntn/hil/gate.hpp): every fault kind is counted under its own
// name, flagged in its frame, and what the gate passes on is the last good value of each channel.
#include "ntn/hil/gate.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include "support/alloc_counter.hpp"

namespace gate_test {

using namespace ntn::hil;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

// A packet in a fixed buffer, as the loop would receive it.
struct Datagram {
  std::array<std::byte, kMaxPacketBytes> buf{};
  std::size_t size = 0;
  std::span<const std::byte> bytes() const { return {buf.data(), size}; }
};

Datagram input(std::uint32_t seq, std::int64_t frame, std::span<const double> values) {
  Datagram d;
  d.size = encode(PacketKind::kInput, seq, frame, 0, values, d.buf);
  return d;
}
Datagram input(std::uint32_t seq, std::int64_t frame, std::initializer_list<double> values) {
  return input(seq, frame, std::span<const double>(values.begin(), values.size()));
}

// Three channels: a ground acceleration in g within [-3, 3], another, and a force in [-100, 100].
InputGate make_gate() {
  std::array<ntn::InputSpec, 3> in{};
  in[0].min = -3, in[0].max = 3;
  in[1].min = -3, in[1].max = 3;
  in[2].min = -100, in[2].max = 100;
  in[2].kind = ntn::InputKind::kNodalForce;
  return InputGate(in);
}

struct Frame {
  std::array<double, 3> v{};
  std::uint16_t flags = 0;
};

// One frame: begin, offer each datagram, end.
Frame run_frame(InputGate& g, std::int64_t k, std::initializer_list<Datagram> datagrams) {
  EXPECT_TRUE(g.begin_frame(k));
  for (const Datagram& d : datagrams)
    g.offer(d.bytes());
  Frame f;
  g.end_frame(f.v, f.flags);
  return f;
}

// Value of channel c at frame k in the clean streams below: in range (|v| < 2.1), distinct for
// frames less than 200 apart.
double clean(int c, std::int64_t k) {
  return 0.01 * static_cast<double>(k % 200) + 0.1 * c;
}
Datagram clean_packet(std::int64_t k) {
  return input(static_cast<std::uint32_t>(k), k, {clean(0, k), clean(1, k), clean(2, k)});
}

TEST(Gate, CleanStreamPassesValuesUnchanged) {
  InputGate g = make_gate();
  ASSERT_TRUE(g.valid());
  for (std::int64_t k = 0; k < 50; ++k) {
    const Frame f = run_frame(g, k, {clean_packet(k)});
    EXPECT_EQ(f.flags, 0);
    for (int c = 0; c < 3; ++c)
      EXPECT_EQ(f.v[static_cast<std::size_t>(c)], clean(c, k));
  }
  const GateCounters& n = g.counters();
  EXPECT_EQ(n.accepted, 50u);
  EXPECT_EQ(n.missing + n.corrupt + n.late + n.duplicate + n.early + n.reordered, 0u);
}

// NaN, +Inf, -Inf and out-of-range values each hold that channel only; the others pass.
TEST(Gate, BadValuesHoldTheirChannel) {
  InputGate g = make_gate();
  run_frame(g, 0, {input(0, 0, {0.5, -0.5, 50})});
  Frame f = run_frame(g, 1, {input(1, 1, {kNaN, -0.25, 20})});
  EXPECT_EQ(f.v, (std::array<double, 3>{0.5, -0.25, 20}));
  EXPECT_EQ(f.flags, flag::kNonFinite | flag::kHeld);
  EXPECT_EQ(g.held_channels(), 0b001u);
  f = run_frame(g, 2, {input(2, 2, {0.75, kInf, -kInf})});
  EXPECT_EQ(f.v, (std::array<double, 3>{0.75, -0.25, 20}));
  EXPECT_EQ(g.held_channels(), 0b110u);
  f = run_frame(g, 3, {input(3, 3, {3.0, -3.0000001, 100.5})});  // 3.0 is in range (inclusive)
  EXPECT_EQ(f.v, (std::array<double, 3>{3.0, -0.25, 20}));
  EXPECT_EQ(f.flags, flag::kOutOfRange | flag::kHeld);
  EXPECT_EQ(g.held_channels(), 0b110u);
  EXPECT_EQ(g.counters().nonfinite, 3u);
  EXPECT_EQ(g.counters().out_of_range, 2u);
  EXPECT_EQ(g.counters().accepted, 4u);
}

// Before any good value a channel holds 0, or the configured initial value, or (when 0 is out
// of range) the nearer end of its range.
TEST(Gate, InitialHeldValues) {
  InputGate g(3);
  ASSERT_TRUE(g.set_range(1, 2.0, 5.0));
  ASSERT_TRUE(g.set_range(2, -1.0, 1.0));
  ASSERT_TRUE(g.set_initial(2, 0.5));
  EXPECT_FALSE(g.set_initial(2, 1.5));   // out of range
  EXPECT_FALSE(g.set_initial(0, kNaN));  // not finite
  EXPECT_FALSE(g.set_range(0, 1.0, -1.0));
  EXPECT_FALSE(g.set_range(3, 0.0, 1.0));
  const Frame f = run_frame(g, 0, {input(0, 0, {kNaN, kNaN, kNaN})});
  EXPECT_EQ(f.v, (std::array<double, 3>{0.0, 2.0, 0.5}));
  EXPECT_FALSE(g.set_initial(0, 1.0));  // after the first frame: refused
}

// A burst of bad values and missing frames: not one output value is non-finite or out of
// range, and every one equals the last good value before the burst.
TEST(Gate, NaNBurstGivesNoNaN) {
  InputGate g = make_gate();
  run_frame(g, 0, {clean_packet(0)});
  const std::array<double, 3> good{clean(0, 0), clean(1, 0), clean(2, 0)};
  const double bad[] = {kNaN, -kNaN, kInf, -kInf, 1e308, -400.0};  // -b bad as well
  for (std::int64_t k = 1; k <= 600; ++k) {
    const double b = bad[k % 6];
    Frame f;
    if (k % 7 == 0) {
      f = run_frame(g, k, {});  // missing as well
    } else {
      f = run_frame(g, k, {input(static_cast<std::uint32_t>(k), k, {b, b, -b})});
    }
    for (std::size_t c = 0; c < 3; ++c) {
      ASSERT_TRUE(std::isfinite(f.v[c])) << "frame " << k;
      ASSERT_EQ(f.v[c], good[c]) << "frame " << k;
    }
    EXPECT_TRUE(f.flags & flag::kHeld);
  }
  const Frame after = run_frame(g, 601, {clean_packet(601)});
  EXPECT_EQ(after.flags, 0);
  EXPECT_EQ(after.v[2], clean(2, 601));
}

TEST(Gate, MissingFrameHoldsEverything) {
  InputGate g = make_gate();
  run_frame(g, 0, {clean_packet(0)});
  const Frame f = run_frame(g, 1, {});
  EXPECT_EQ(f.v, (std::array<double, 3>{clean(0, 0), clean(1, 0), clean(2, 0)}));
  EXPECT_EQ(f.flags, flag::kMissing | flag::kHeld);
  EXPECT_EQ(g.held_channels(), 0b111u);
  EXPECT_EQ(g.counters().missing, 1u);
  EXPECT_EQ(g.counters().lost(), 1u);  // nothing came later
}

// Frame 1's packet arrives during frame 2: late (dropped), and it was the missing frame's, so
// lost() does not count it. A second, different packet for frame 1 is late but not for a
// missing frame.
TEST(Gate, LatePacketIsDroppedAndReconciled) {
  InputGate g = make_gate();
  run_frame(g, 0, {clean_packet(0)});
  run_frame(g, 1, {});
  const Frame f = run_frame(g, 2, {clean_packet(1), clean_packet(2)});
  EXPECT_EQ(f.v[0], clean(0, 2));
  EXPECT_EQ(f.flags, flag::kLate);
  run_frame(g, 3, {input(1000, 1, {0, 0, 0})});  // another sequence, frame 1 again
  const GateCounters& n = g.counters();
  EXPECT_EQ(n.late, 2u);
  EXPECT_EQ(n.late_for_missing, 1u);
  EXPECT_EQ(n.missing, 2u);    // frames 1 and 3
  EXPECT_EQ(n.lost(), 1u);     // frame 3's packet never came
  EXPECT_EQ(n.reordered, 0u);  // 0, 1, 2, 1000: late, but never behind the newest sequence
}

// Frame indices at the ends of int64 (found by the packet fuzzer: INT64_MIN overflowed the
// late-packet arithmetic, UB caught by UBSan): neither is a frame of the run (out_of_run), and
// the stream goes on unchanged.
TEST(Gate, ExtremeFrameIndicesAreOutOfTheRun) {
  InputGate g = make_gate();
  run_frame(g, 0, {clean_packet(0)});
  const Frame f =
      run_frame(g, 1,
                {clean_packet(1), input(2, std::numeric_limits<std::int64_t>::min(), {0, 0, 0}),
                 input(3, std::numeric_limits<std::int64_t>::max(), {0, 0, 0})});
  EXPECT_EQ(f.v[0], clean(0, 1));
  EXPECT_EQ(f.flags, flag::kBadFrame);
  EXPECT_EQ(g.counters().out_of_run, 2u);
  EXPECT_EQ(g.counters().late, 0u);
  EXPECT_EQ(g.counters().too_early, 0u);
  EXPECT_EQ(g.counters().late_for_missing, 0u);
}

// Regression: one valid packet for frame 18 445 744 073 710 (of a 1000-frame run) hung the
// loop. The gate rejects a frame outside the run (out_of_run) or more than kFrameWindow frames
// from the current one (out_of_window), before any sequence check: such a packet changes
// nothing, not even the sequence window (its sequence 10^6 ahead would otherwise make every later
// packet "reordered").
TEST(Gate, FramesOutsideTheRunOrTheWindowAreRejected) {
  InputGate g = make_gate();
  EXPECT_FALSE(g.set_run_frames(0));
  ASSERT_TRUE(g.set_run_frames(5000));
  EXPECT_EQ(g.run_frames(), 5000);
  ASSERT_TRUE(g.begin_frame(0));
  EXPECT_EQ(g.offer(input(1'000'000, 18'445'744'073'710, {0, 0, 0}).bytes()).status,
            OfferStatus::kOutOfRun);
  EXPECT_EQ(g.offer(input(1'000'001, 5000, {0, 0, 0}).bytes()).status, OfferStatus::kOutOfRun);
  EXPECT_EQ(g.offer(input(1'000'002, -1, {0, 0, 0}).bytes()).status, OfferStatus::kOutOfRun);
  EXPECT_EQ(g.offer(input(1'000'003, InputGate::kFrameWindow + 1, {0, 0, 0}).bytes()).status,
            OfferStatus::kOutOfWindow);
  EXPECT_EQ(g.offer(clean_packet(0).bytes()).status, OfferStatus::kCurrent);
  Frame f;
  g.end_frame(f.v, f.flags);
  EXPECT_EQ(f.flags, flag::kBadFrame);
  for (std::int64_t k = 1; k < 1000; ++k) {
    f = run_frame(g, k, {clean_packet(k)});
    ASSERT_EQ(f.flags, 0) << k;
  }
  // The window follows the current frame: 1024 behind is late, 1025 behind is out of the window.
  g = make_gate();
  for (std::int64_t k = 0; k <= 2000; ++k)
    run_frame(g, k, {clean_packet(k)});
  ASSERT_TRUE(g.begin_frame(2001));
  EXPECT_EQ(g.offer(input(5000, 2001 - InputGate::kFrameWindow, {0, 0, 0}).bytes()).status,
            OfferStatus::kLate);
  EXPECT_EQ(g.offer(input(5001, 2000 - InputGate::kFrameWindow, {0, 0, 0}).bytes()).status,
            OfferStatus::kOutOfWindow);
  EXPECT_EQ(g.accept_values(2001 + InputGate::kFrameWindow + 1, std::array<double, 3>{}).status,
            OfferStatus::kOutOfWindow);
  const GateCounters& n = g.counters();
  EXPECT_EQ(n.accepted, 2001u);
  EXPECT_EQ(n.reordered, 0u);
  EXPECT_EQ(n.out_of_window, 2u);
  EXPECT_EQ(n.late, 1u);
}

// A sender that restarts its sequence numbers while its frames go on. Before,
// a restart at 0 after 300 packets lost those 300 as duplicates; a restart after more than
// kSequenceWindow packets marked every later packet reordered. Rule: a sequence not above the
// newest, on a packet whose frame is newer than every frame seen, is a sender restart (counted
// once): the sequence window is re-based on it and the packet is used.
TEST(Gate, SenderRestartRebasesTheSequence) {
  for (const std::int64_t restart_at : {std::int64_t{300}, std::int64_t{1500}}) {
    InputGate g = make_gate();
    const std::int64_t frames = 2 * restart_at;
    for (std::int64_t k = 0; k < frames; ++k) {
      const auto seq = static_cast<std::uint32_t>(k < restart_at ? k : k - restart_at);
      const Frame f = run_frame(g, k, {input(seq, k, {clean(0, k), clean(1, k), clean(2, k)})});
      ASSERT_EQ(f.flags, 0) << "restart at " << restart_at << ", frame " << k;
      ASSERT_EQ(f.v[0], clean(0, k));
    }
    const GateCounters& n = g.counters();
    EXPECT_EQ(n.accepted, static_cast<std::uint64_t>(frames)) << restart_at;
    EXPECT_EQ(n.sender_restart, 1u);
    EXPECT_EQ(n.duplicate, 0u);
    EXPECT_EQ(n.reordered, 0u);
    EXPECT_EQ(n.missing, 0u);
  }
  // Not restarts: a resent copy (same sequence, same frame), a reordered pair (older sequence,
  // older frame), a second packet for a frame.
  InputGate g = make_gate();
  const Datagram p0 = clean_packet(0);
  run_frame(g, 0, {p0, p0});
  ASSERT_TRUE(g.begin_frame(1));
  g.offer(clean_packet(2).bytes());
  g.offer(clean_packet(1).bytes());
  g.offer(input(1, 1, {0, 0, 0}).bytes());
  Frame f;
  g.end_frame(f.v, f.flags);
  run_frame(g, 2, {p0});
  EXPECT_EQ(g.counters().sender_restart, 0u);
  EXPECT_EQ(g.counters().duplicate, 3u);
  EXPECT_EQ(g.counters().reordered, 1u);
  // A restart to a sequence just below the newest, and one that lands on a sequence seen in the
  // window (a duplicate before): both recognised by the newer frame.
  run_frame(g, 3, {input(1, 3, {0, 0, 0})});
  run_frame(g, 4, {input(0, 4, {0, 0, 0})});
  EXPECT_EQ(g.counters().sender_restart, 2u);
  EXPECT_EQ(g.counters().accepted, 5u);
}

TEST(Gate, DuplicatesAreDropped) {
  InputGate g = make_gate();
  const Datagram p0 = clean_packet(0);
  Frame f = run_frame(g, 0, {p0, p0});
  EXPECT_EQ(f.flags, flag::kDuplicate);
  EXPECT_EQ(f.v[0], clean(0, 0));
  // The same sequence again one frame on: a duplicate, not late.
  f = run_frame(g, 1, {clean_packet(1), p0});
  EXPECT_EQ(f.flags, flag::kDuplicate);
  // A new sequence for a frame that already has a packet: duplicate too; the first one is kept.
  f = run_frame(g, 2, {clean_packet(2), input(77, 2, {1, 1, 1})});
  EXPECT_EQ(f.v[0], clean(0, 2));
  const GateCounters& n = g.counters();
  EXPECT_EQ(n.duplicate, 3u);
  EXPECT_EQ(n.late, 0u);
  EXPECT_EQ(n.accepted, 3u);
}

// Packets for frames k+2, k+1, k arrive in that order during frame k: the two early ones wait
// in the jitter buffer and are used at their frames; two packets came out of sequence order.
TEST(Gate, JitterBufferReorders) {
  InputGate g = make_gate();
  run_frame(g, 0, {clean_packet(0)});
  EXPECT_TRUE(g.begin_frame(1));
  EXPECT_EQ(g.offer(clean_packet(3).bytes()).status, OfferStatus::kBuffered);
  EXPECT_EQ(g.offer(clean_packet(2).bytes()).status, OfferStatus::kBuffered);
  EXPECT_EQ(g.offer(clean_packet(1).bytes()).status, OfferStatus::kCurrent);
  Frame f;
  g.end_frame(f.v, f.flags);
  EXPECT_EQ(f.flags, flag::kEarly | flag::kReordered);
  EXPECT_EQ(f.v[1], clean(1, 1));
  for (std::int64_t k = 2; k <= 3; ++k) {
    f = run_frame(g, k, {});
    EXPECT_EQ(f.flags, 0) << k;
    EXPECT_EQ(f.v[1], clean(1, k));
  }
  const GateCounters& n = g.counters();
  EXPECT_EQ(n.early, 2u);
  EXPECT_EQ(n.reordered, 2u);
  EXPECT_EQ(n.accepted, 4u);
  EXPECT_EQ(n.missing, 0u);
}

TEST(Gate, TooEarlyBeyondTheJitterBuffer) {
  InputGate g = make_gate();
  ASSERT_TRUE(g.begin_frame(10));
  EXPECT_EQ(g.offer(clean_packet(10 + InputGate::kJitterFrames).bytes()).status,
            OfferStatus::kBuffered);
  EXPECT_EQ(g.offer(clean_packet(11 + InputGate::kJitterFrames).bytes()).status,
            OfferStatus::kTooEarly);
  Frame f;
  g.end_frame(f.v, f.flags);
  EXPECT_EQ(f.flags, flag::kEarly | flag::kTooEarly | flag::kMissing | flag::kHeld);
  EXPECT_EQ(g.counters().too_early, 1u);
}

TEST(Gate, WrongCountAndCorrupt) {
  InputGate g = make_gate();
  run_frame(g, 0, {clean_packet(0)});
  Datagram bad = clean_packet(1);
  bad.buf[kHeaderBytes] ^= std::byte{1};  // checksum no longer matches
  Datagram out;
  const double v3[3] = {9, 9, 9};
  out.size = encode(PacketKind::kOutput, 1, 1, 0, v3, out.buf);  // an output packet, misrouted
  Datagram shortd = clean_packet(1);
  shortd.size = 10;
  const Frame f = run_frame(g, 1, {input(1, 1, {0.1, 0.2}), bad, out, shortd});
  EXPECT_EQ(f.v, (std::array<double, 3>{clean(0, 0), clean(1, 0), clean(2, 0)}));
  EXPECT_EQ(f.flags, flag::kWrongCount | flag::kCorrupt | flag::kMissing | flag::kHeld);
  const GateCounters& n = g.counters();
  EXPECT_EQ(n.wrong_count, 1u);
  EXPECT_EQ(n.corrupt, 3u);
  EXPECT_EQ(n.decode_errors[static_cast<std::size_t>(DecodeError::kChecksum)], 1u);
  EXPECT_EQ(n.decode_errors[static_cast<std::size_t>(DecodeError::kKind)], 1u);
  EXPECT_EQ(n.decode_errors[static_cast<std::size_t>(DecodeError::kShort)], 1u);
  // The wrong-count packet's sequence was not taken: the right packet with it is accepted.
  const Frame f2 = run_frame(g, 2, {input(1, 2, {0.1, 0.2, 0.3})});
  EXPECT_EQ(f2.v, (std::array<double, 3>{0.1, 0.2, 0.3}));
}

TEST(Gate, FrameEndMarkerIsNotAnInput) {
  InputGate g = make_gate();
  ASSERT_TRUE(g.begin_frame(0));
  Datagram e;
  e.size = encode(PacketKind::kFrameEnd, 0, 0, 0, {}, e.buf);
  const OfferResult r = g.offer(e.bytes());
  EXPECT_EQ(r.status, OfferStatus::kFrameEnd);
  EXPECT_EQ(r.frame, 0);
  EXPECT_EQ(g.offer(clean_packet(0).bytes()).status, OfferStatus::kCurrent);
  Frame f;
  g.end_frame(f.v, f.flags);
  EXPECT_EQ(f.flags, 0);
  EXPECT_EQ(g.counters().frame_ends, 1u);
  EXPECT_EQ(g.counters().accepted, 1u);
}

TEST(Gate, FramesMustIncreaseAndOffersNeedAFrame) {
  InputGate g = make_gate();
  EXPECT_EQ(g.offer(clean_packet(0).bytes()).status, OfferStatus::kNotInFrame);
  run_frame(g, 5, {clean_packet(5)});
  EXPECT_FALSE(g.begin_frame(5));
  EXPECT_FALSE(g.begin_frame(4));
  EXPECT_EQ(g.offer(clean_packet(6).bytes()).status, OfferStatus::kNotInFrame);
  EXPECT_EQ(g.counters().accepted, 1u);
  EXPECT_EQ(g.counters().early, 0u);
}

// Skipped frames are closed as if ended: a buffered packet is used (its values become the last
// good), the others are missing; their flags reach the next frame.
TEST(Gate, SkippedFramesAreClosed) {
  InputGate g = make_gate();
  ASSERT_TRUE(g.begin_frame(0));
  g.offer(clean_packet(0).bytes());
  g.offer(clean_packet(2).bytes());
  Frame f;
  g.end_frame(f.v, f.flags);
  f = run_frame(g, 5, {});  // frames 1..4 skipped: 2 used, 1, 3, 4 missing
  EXPECT_EQ(f.v[0], clean(0, 2));
  EXPECT_TRUE(f.flags & flag::kMissing);
  EXPECT_EQ(g.counters().missing, 4u);  // 1, 3, 4 and 5
  EXPECT_EQ(g.counters().accepted, 2u);
  // A long jump is counted without visiting every frame.
  f = run_frame(g, 5 + 1'000'000'000LL, {});
  EXPECT_EQ(g.counters().missing, 4u + 1'000'000'000ULL);
  // A packet for a frame counted missing in the jump (within the missing window) reconciles.
  run_frame(g, 6 + 1'000'000'000LL, {clean_packet(1'000'000'000LL)});
  EXPECT_EQ(g.counters().late_for_missing, 1u);
}

// File source: values go through the same checks, without packets.
TEST(Gate, AcceptValuesFromAFile) {
  InputGate g = make_gate();
  const std::array<std::array<double, 3>, 4> rows{
      {{0.5, 0.5, 5}, {kNaN, 0.6, 500}, {0.7, 0.7, 7}, {0.8, 0.8, 8}}};
  std::array<double, 3> out{};
  std::uint16_t flags = 0;
  for (std::int64_t k = 0; k < 3; ++k) {
    ASSERT_TRUE(g.begin_frame(k));
    EXPECT_EQ(g.accept_values(k, rows[static_cast<std::size_t>(k)]).status, OfferStatus::kCurrent);
    g.end_frame(out, flags);
  }
  EXPECT_EQ(out, (std::array<double, 3>{0.7, 0.7, 7}));
  ASSERT_TRUE(g.begin_frame(3));
  EXPECT_EQ(g.accept_values(3, std::span(rows[3]).first(2)).status, OfferStatus::kWrongCount);
  EXPECT_EQ(g.accept_values(2, rows[3]).status, OfferStatus::kLate);
  g.end_frame(out, flags);
  EXPECT_EQ(out, (std::array<double, 3>{0.7, 0.7, 7}));
  EXPECT_EQ(g.counters().nonfinite, 1u);
  EXPECT_EQ(g.counters().out_of_range, 1u);
  EXPECT_EQ(g.counters().missing, 1u);
}

// The u32 sequence wraps: 0xFFFFFFFF then 0 is in order; a sequence a full window behind the
// newest cannot be checked for duplication and goes on to the frame rules.
TEST(Gate, SequenceWrapAndOldSequences) {
  InputGate g = make_gate();
  run_frame(g, 0, {input(0xFFFFFFFEU, 0, {0, 0, 0})});
  run_frame(g, 1, {input(0xFFFFFFFFU, 1, {0, 0, 0})});
  run_frame(g, 2, {input(0, 2, {0, 0, 0})});
  run_frame(g, 3, {input(1, 3, {0, 0, 0})});
  EXPECT_EQ(g.counters().reordered, 0u);
  EXPECT_EQ(g.counters().accepted, 4u);
  run_frame(g, 4, {input(1 + InputGate::kSequenceWindow, 4, {0, 0, 0}), input(1, 3, {0, 0, 0})});
  EXPECT_EQ(g.counters().duplicate, 0u);  // out of the window: not known
  EXPECT_EQ(g.counters().late, 1u);
  EXPECT_EQ(g.counters().reordered, 1u);
}

TEST(Gate, BadChannelCountMakesAnInvalidGate) {
  EXPECT_FALSE(InputGate(kMaxChannels + 1).valid());
  EXPECT_FALSE(InputGate(-1).valid());
  EXPECT_TRUE(InputGate(kMaxChannels).valid());
  std::array<ntn::InputSpec, 1> bad{};
  bad[0].min = 1, bad[0].max = 0;
  EXPECT_FALSE(InputGate(bad).valid());
}

// Real-time paths do not allocate: encode, decode, offer of every kind of datagram, end_frame
// and accept_values over 20 000 frames.
TEST(Gate, NoAllocationInTheFramePath) {
  InputGate g = make_gate();
  std::array<double, 3> out{};
  std::uint16_t flags = 0;
  Datagram d, e;
  const ntn_test::AllocationScope scope;
  for (std::int64_t k = 0; k < 20'000; ++k) {
    const auto seq = static_cast<std::uint32_t>(k);
    const double v[3] = {k % 11 == 0 ? kNaN : clean(0, k % 100), clean(1, k % 100),
                         k % 13 == 0 ? 1e9 : clean(2, k % 100)};
    g.begin_frame(k);
    switch (k % 10) {
      case 0:
        break;  // missing
      case 1:   // duplicate, and a late one
        d.size = encode(PacketKind::kInput, seq, k, 0, v, d.buf);
        g.offer(d.bytes());
        g.offer(d.bytes());
        d.size = encode(PacketKind::kInput, seq - 1, k - 1, 0, v, d.buf);
        g.offer(d.bytes());
        break;
      case 2:  // early for the next frame, then this one
        d.size = encode(PacketKind::kInput, seq + 1, k + 1, 0, v, d.buf);
        g.offer(d.bytes());
        d.size = encode(PacketKind::kInput, seq, k, 0, v, d.buf);
        g.offer(d.bytes());
        break;
      case 3:
        break;  // already buffered
      case 4:   // corrupt, wrong count, then good
        d.size = encode(PacketKind::kInput, seq, k, 0, v, d.buf);
        e = d;
        e.buf[5] ^= std::byte{0x40};
        g.offer(e.bytes());
        e.size = encode(PacketKind::kInput, seq, k, 0, std::span(v, 2), e.buf);
        g.offer(e.bytes());
        g.offer(d.bytes());
        break;
      case 5:
        g.accept_values(k, v);
        break;
      default: {
        d.size = encode(PacketKind::kInput, seq, k, 0, v, d.buf);
        Packet p;
        EXPECT_EQ(decode(d.bytes(), p), DecodeError::kOk);
        g.offer(d.bytes());
      }
    }
    g.end_frame(out, flags);
    ASSERT_TRUE(std::isfinite(out[0]));
  }
  const ntn_test::AllocationCounts n = scope.counts();
  EXPECT_EQ(n.allocations, 0u);
  EXPECT_EQ(n.deallocations, 0u);
  EXPECT_EQ(g.counters().accepted + g.counters().missing, 20'000u);
  EXPECT_GT(g.counters().corrupt, 0u);
  EXPECT_GT(g.counters().late, 0u);
  EXPECT_GT(g.counters().nonfinite, 0u);
}

}  // namespace gate_test
