// PNG encoders on worker threads for frame sequences (private to pelage::render): the renderer's
// thread hands over rendered images (blocking while every image buffer is in use, which bounds
// memory) and gets the buffers back when the files are written.
#pragma once

#include <condition_variable>
#include <deque>
#include <exception>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "pelage/render/image.h"

namespace pelage::render::detail {

// Writes one finished file (the sequence's FileWriter).
using WriteFile =
    std::function<void(const std::string& path, const std::vector<std::uint8_t>& bytes)>;

// PNG encoders on worker threads: the main thread hands over rendered images (blocking while every
// image buffer is in use, which bounds memory) and gets the buffers back when the files are
// written.
class EncoderPool {
 public:
  EncoderPool(int threads, int width, int height, WriteFile writer,
              std::function<void(int)> onWritten)
      : writer_(std::move(writer)), onWritten_(std::move(onWritten)) {
    const int buffers = threads + 2;
    for (int i = 0; i < buffers; ++i) {
      auto img = std::make_unique<Image>();
      img->width = width;
      img->height = height;
      img->rgba.resize(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 4);
      free_.push_back(std::move(img));
    }
    for (int i = 0; i < threads; ++i) workers_.emplace_back([this] { work(); });
  }
  ~EncoderPool() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      stop_ = true;
    }
    cv_.notify_all();
    for (std::thread& t : workers_) t.join();
  }

  // A free image buffer (waits for one); rethrows an encoder's error.
  std::unique_ptr<Image> acquire() {
    std::unique_lock<std::mutex> lock(mutex_);
    cv_.wait(lock, [this] { return !free_.empty() || error_; });
    if (error_) std::rethrow_exception(error_);
    std::unique_ptr<Image> img = std::move(free_.back());
    free_.pop_back();
    return img;
  }
  void submit(int frame, std::string path, std::unique_ptr<Image> image) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      jobs_.push_back(Job{frame, std::move(path), std::move(image)});
    }
    cv_.notify_all();
  }
  // Waits until every submitted frame is written; rethrows the first error.
  void drain() {
    std::unique_lock<std::mutex> lock(mutex_);
    cv_.wait(lock, [this] { return (jobs_.empty() && busy_ == 0) || error_; });
    if (error_) std::rethrow_exception(error_);
  }

 private:
  struct Job {
    int frame = 0;
    std::string path;
    std::unique_ptr<Image> image;
  };
  void work() {
    for (;;) {
      Job job;
      {
        std::unique_lock<std::mutex> lock(mutex_);
        cv_.wait(lock, [this] { return stop_ || (!jobs_.empty() && !error_); });
        if (stop_) return;
        job = std::move(jobs_.front());
        jobs_.pop_front();
        ++busy_;
      }
      std::exception_ptr err;
      try {
        const std::vector<std::uint8_t> png = encodePng(*job.image);
        writer_(job.path, png);
      } catch (...) {
        err = std::current_exception();
      }
      {
        std::lock_guard<std::mutex> lock(mutex_);
        --busy_;
        free_.push_back(std::move(job.image));
        if (err && !error_) error_ = err;
        if (!err) onWritten_(job.frame);  // under the lock: one progress report at a time
      }
      cv_.notify_all();
    }
  }

  WriteFile writer_;
  std::function<void(int)> onWritten_;
  std::mutex mutex_;
  std::condition_variable cv_;
  std::deque<Job> jobs_;
  std::vector<std::unique_ptr<Image>> free_;
  std::vector<std::thread> workers_;
  std::exception_ptr error_;
  int busy_ = 0;
  bool stop_ = false;
};

}  // namespace pelage::render::detail
