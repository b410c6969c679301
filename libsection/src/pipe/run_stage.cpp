// SPDX-License-Identifier: GPL-3.0-or-later
// The part scheduler: a stage of the pipe run over the parts of a stream as they are read,
// several at a time, each written as soon as it and the parts before it are done.
#include "section/pipe/run_stage.h"

#include "detail/parallel.h"
#include "io/stream_text.h"
#include "section/error.h"
#include "section/io/stream_reader.h"
#include "section/pipe/schema.h"
#include "section/units.h"
#include "section/pipe/validate.h"

#include <condition_variable>
#include <deque>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace section {

namespace {

// Refuses a stream in a length unit the stages cannot convert to mm.
void check_units(const std::string& units, const std::string& source) {
  try {
    mm_per_unit(units);
  } catch (const Error& e) {
    throw Error("pipe: " + source + ": " + e.what());
  }
}

// A stream not split into parts: read, staged and written whole.
void run_whole(const StageRun& run, PartReader& reader) {
  std::string text = reader.whole();
  const std::size_t bom = text.rfind("\xEF\xBB\xBF", 0) == 0 ? 3 : 0;  // parse_stream skips it
  Stream stream = run.other_input && text.compare(bom, 19, "# libsection-stream") != 0
                      ? run.other_input(text, reader.source())
                      : parse_stream(std::make_shared<const std::string>(std::move(text)), reader.source());
  check_units(stream.units, reader.source());
  validate_stream(stream, reader.source());
  convert_to_mm(stream);
  if (run.preamble) run.preamble(stream);
  run.stage(stream, run.threads);
  stream.history.push_back(run.history);
  if (run.hold) run.hold({&stream});
  if (run.written) run.written(stream);
  if (run.before_end) run.before_end();
  write_stream(run.output, stream);
}

// Parts are staged by the workers as they are read, and written in order by whichever
// thread finds the front part finished: the worker that finished it, or the thread that
// reads them (which may wait for input while a finished part is due downstream).
class PartScheduler {
public:
  PartScheduler(const StageRun& run, PartReader& reader, const Stream& head, const std::string& units)
      : run_(run),
        reader_(reader),
        units_(units),
        writer_(run.output, head),
        workers_(run.threads > 0 ? std::size_t(run.threads)
                                 : std::max<std::size_t>(1, std::thread::hardware_concurrency())),
        // Converted to mm, a table is written from its values: all are decoded then.
        unread_(run.unread.empty() || mm_per_unit(units) != 1 ? nullptr : &run.unread) {}

  void run() {
    std::vector<std::thread> pool = detail::start_threads(workers_, [this] { work(); });
    if (pool.empty()) return run_alone();  // no thread could start (a low ulimit -v)
    try {
      StreamPart part;
      while (reader_.next(part))
        if (!submit(std::move(part))) break;  // a part has failed: no use reading on
      write_done(false, true);
    } catch (...) {
      std::lock_guard<std::mutex> lock(mutex_);
      if (!error_) error_ = std::current_exception();
    }
    {
      std::lock_guard<std::mutex> lock(mutex_);
      input_done_ = true;
    }
    changed_.notify_all();
    for (auto& t : pool) t.join();
    if (error_) std::rethrow_exception(error_);
    write_held();
    if (run_.before_end) run_.before_end();
    writer_.finish();
  }

private:
  struct Job {
    StreamPart part;  // its text is kept by the tables passed through (Table::source)
    Stream result;
    bool done = false;
  };

  // Parses and stages a job's part (its text is then released).
  void stage(Job& job) {
    // (the parts are the parallel work: one thread a part)
    Stream part = detail::parse_stream_text(*job.part.text, reader_.source(), job.part.text,
                                            detail::PartText{true, job.part.first_line, 1, unread_});
    validate_stream(part, reader_.source());
    part.units = units_;
    convert_to_mm(part);
    run_.stage(part, 1);
    job.part.text = nullptr;
    job.result = std::move(part);
  }

  // Each part read, staged and written in turn, on this thread alone.
  void run_alone() {
    StreamPart part;
    while (reader_.next(part)) {
      Job job{std::move(part), {}, false};
      stage(job);
      if (run_.hold) {
        held_.push_back(std::move(job));
        continue;
      }
      if (run_.written) run_.written(job.result);
      writer_.part(job.part.label, job.result);
    }
    write_held();
    if (run_.before_end) run_.before_end();
    writer_.finish();
  }

  // A worker: stages the parts in turn until the input is done or a part has failed.
  void work() {
    std::unique_lock<std::mutex> lock(mutex_);
    while (true) {
      changed_.wait(lock,
                    [&] { return error_ || next_to_stage_ < first_job_ + jobs_.size() || input_done_; });
      if (error_ || next_to_stage_ >= first_job_ + jobs_.size()) return;
      Job& job = jobs_[next_to_stage_++ - first_job_];
      lock.unlock();
      try {
        stage(job);
        lock.lock();
        job.done = true;
        // Written now if it is at the front: the reading thread may be waiting for the
        // next part's first line, and the stage after this one for this part.
        write_front(lock);
      } catch (...) {
        if (!lock.owns_lock()) lock.lock();
        if (!error_) error_ = std::current_exception();
      }
      changed_.notify_all();
    }
  }

  // Writes the finished parts at the front, in order, unless another thread is writing
  // (it writes them). Called and returns with `lock` held.
  void write_front(std::unique_lock<std::mutex>& lock) {
    while (!error_ && !writing_ && !jobs_.empty() && jobs_.front().done) {
      Job job = std::move(jobs_.front());
      jobs_.pop_front();
      ++first_job_;
      writing_ = true;  // one writer at a time: the parts go out in order
      lock.unlock();
      try {
        if (run_.hold) {
          held_.push_back(std::move(job));
        } else {
          if (run_.written) run_.written(job.result);
          writer_.part(job.part.label, job.result);
        }
      } catch (...) {
        lock.lock();
        writing_ = false;
        changed_.notify_all();
        throw;
      }
      lock.lock();
      writing_ = false;
      changed_.notify_all();
    }
  }

  // Writes the finished parts at the front, in order (with the workers, which write a part
  // finished at the front). With `room`, until fewer than two parts per worker wait (the
  // memory of a pipe stays that of a few sections); with `all`, until every part is written.
  void write_done(bool room, bool all) {
    std::unique_lock<std::mutex> lock(mutex_);
    while (!error_) {
      write_front(lock);
      if (error_) return;
      if (all ? jobs_.empty() && !writing_ : !(room && jobs_.size() >= 2 * workers_)) return;
      changed_.wait(lock, [&] { return error_ || (!writing_ && (jobs_.empty() || jobs_.front().done)); });
    }
  }

  // The parts held for StageRun::hold, given to it and written, in order.
  void write_held() {
    if (!run_.hold) return;
    std::vector<Stream*> parts;
    for (Job& job : held_) parts.push_back(&job.result);
    run_.hold(parts);
    for (Job& job : held_) {
      if (run_.written) run_.written(job.result);
      writer_.part(job.part.label, job.result);
    }
  }

  // Queues a part read; false once a part has failed.
  bool submit(StreamPart part) {
    write_done(true, false);
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (error_) return false;
      jobs_.push_back(Job{std::move(part), {}, false});
    }
    changed_.notify_all();
    return true;
  }

  const StageRun& run_;
  PartReader& reader_;
  const std::string units_;
  StreamWriter writer_;
  const std::size_t workers_;
  const std::vector<std::pair<std::string, std::string>>* const unread_;  // StageRun::unread, or none
  std::deque<Job> jobs_;           // read and not yet written, in order (references stay valid)
  std::vector<Job> held_;          // staged and held for StageRun::hold, in order
  std::size_t first_job_ = 0;      // index of jobs_.front()
  std::size_t next_to_stage_ = 0;  // index of the next job a worker takes
  std::mutex mutex_;
  std::condition_variable changed_;
  bool input_done_ = false;
  bool writing_ = false;  // a thread is writing a part (taken off jobs_)
  std::exception_ptr error_;
};

}  // namespace

void run_stage(const StageRun& run) {
  PartReader reader(run.input);
  if (!reader.parted()) return run_whole(run, reader);
  Stream head = reader.preamble();
  const std::string units = head.units;
  check_units(units, reader.source());  // before anything is written
  head.units = "mm";                    // each part is converted to mm before it is staged
  head.history.push_back(run.history);
  if (run.preamble) run.preamble(head);
  PartScheduler(run, reader, head, units).run();
}

}  // namespace section
