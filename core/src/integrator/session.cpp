#include "torrance/integrator/session.h"

#include <stdexcept>

namespace torrance {

RenderSession::RenderSession(std::shared_ptr<Scene> scene, RenderSettings settings)
    : scene_(std::move(scene)), settings_(std::move(settings)) {
  if (!scene_) throw std::invalid_argument("RenderSession needs a Scene, got None");
  settings_.validate();
}

RenderSession::~RenderSession() { stop(); }

void RenderSession::start() {
  if (thread_.joinable() || finished_) return;
  scene_->begin_render(settings_.light_selection);  // in use from now on, not from when the thread runs
  running_ = true;
  try {
    launch();
  } catch (...) {
    scene_->end_render();
    running_ = false;
    throw;
  }
}

void RenderSession::launch() {
  thread_ = std::thread([this] {
    RenderCallbacks callbacks;
    std::vector<std::pair<std::string, Image>> pending_passes;  // on_pass_passes -> on_pass
    if (settings_.passes)
      callbacks.on_pass_passes = [&pending_passes](std::vector<std::pair<std::string, Image>>&& passes) {
        pending_passes = std::move(passes);
      };
    callbacks.on_pass = [this, &pending_passes](const Image& image, int done, int) {
      std::lock_guard<std::mutex> lock(mutex_);
      image_ = image;
      passes_ = std::move(pending_passes);
      samples_done_ = done;
      ++version_;
    };
    callbacks.should_stop = [this] { return stop_.load(); };
    try {
      RenderResult result = render(*scene_, settings_, callbacks);
      std::lock_guard<std::mutex> lock(mutex_);
      if (result.samples_done > samples_done_ || version_ == 0) {
        image_ = std::move(result.image);
        passes_ = std::move(result.passes);
        samples_done_ = result.samples_done;
        ++version_;
      }
    } catch (const std::exception& e) {
      std::lock_guard<std::mutex> lock(mutex_);
      error_ = e.what();
    }
    scene_->end_render();
    finished_ = true;
    running_ = false;
  });
}

void RenderSession::request_stop() { stop_ = true; }

void RenderSession::stop() {
  stop_ = true;
  if (thread_.joinable()) thread_.join();
  running_ = false;
}

bool RenderSession::latest(Image& image, int& samples_done, uint64_t& version,
                           std::vector<std::pair<std::string, Image>>* passes) const {
  std::lock_guard<std::mutex> lock(mutex_);
  if (version_ == version) return false;
  image = image_;
  if (passes) *passes = passes_;
  samples_done = samples_done_;
  version = version_;
  return true;
}

std::string RenderSession::error() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return error_;
}

}  // namespace torrance
