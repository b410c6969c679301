// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// @file progress.h
/// An optional progress and cancel hook for long calls (reading a large scan, slicing many
/// planes), for a host program's progress bar and cancel button. docs/API.md lists the calls
/// that take one.
#include "section/error.h"

#include <cstddef>
#include <functional>
#include <mutex>
#include <string>

namespace section {

/// What a long call has done so far.
struct ProgressEvent {
  const char* stage = "";  ///< what is going on: "read" (points read), "slice" (sections done)
  std::size_t done = 0;    ///< items done so far (points, sections), growing
  std::size_t total = 0;   ///< items in all, 0 when not known beforehand (a text file's points)
};

/// Told of progress, from one thread at a time (not always the caller's); returns false to
/// cancel the call, which then throws section::Cancelled as soon as it can. It must not call
/// back into the call it watches.
using ProgressFn = std::function<bool(const ProgressEvent&)>;

/// Thrown by a call whose progress function asked to cancel it.
class Cancelled : public Error {
public:
  explicit Cancelled(const std::string& stage) : Error(stage + ": cancelled") {}
};

/// Counts the items of a long call for a ProgressFn, from any number of threads: each add()
/// reports the new count under a lock; once the function has asked to cancel, add() throws
/// Cancelled (and reports no more).
class ProgressCounter {
public:
  ProgressCounter(const ProgressFn& fn, const char* stage, std::size_t total) : fn_(fn) {
    event_.stage = stage;
    event_.total = total;
  }
  /// Adds `n` items done; throws Cancelled when the function returns false (now or before).
  void add(std::size_t n) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (!cancelled_ && fn_) {
      event_.done += n;
      cancelled_ = !fn_(event_);
    }
    if (cancelled_) throw Cancelled(event_.stage);
  }
  std::size_t done() const { return event_.done; }

private:
  const ProgressFn& fn_;
  ProgressEvent event_;
  std::mutex mutex_;
  bool cancelled_ = false;
};

}  // namespace section
