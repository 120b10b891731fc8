// A render running in the background, for interactive use (Blender's viewport): start it, read
// the newest progressive image whenever convenient, stop it when the scene or view changes.
// The session owns its scene (shared), so the caller may drop its own references.
#pragma once

#include "torrance/integrator/integrator.h"

#include <atomic>
#include <memory>
#include <mutex>
#include <thread>

namespace torrance {

class RenderSession {
 public:
  // The settings' passes (if any) come with every image: latest(..., &passes).
  RenderSession(std::shared_ptr<Scene> scene, RenderSettings settings);
  ~RenderSession();  // stops and joins
  RenderSession(const RenderSession&) = delete;
  RenderSession& operator=(const RenderSession&) = delete;

  void start();  // no-op if already started; the scene is in use (read-only) until the render ends
  void stop();          // asks the render to stop and waits for it (well under a second)
  void request_stop();  // asks the render to stop and returns at once (stop() or the destructor joins)

  // The newest image if it changed since the last call (version increases with every pass), and
  // with `passes` the settings' passes of the same samples.
  bool latest(Image& image, int& samples_done, uint64_t& version,
              std::vector<std::pair<std::string, Image>>* passes = nullptr) const;
  bool running() const { return running_; }
  bool finished() const { return finished_; }
  std::string error() const;  // what went wrong, if the render failed

 private:
  void launch();
  std::shared_ptr<Scene> scene_;
  RenderSettings settings_;
  std::thread thread_;
  std::atomic<bool> stop_{false}, running_{false}, finished_{false};
  mutable std::mutex mutex_;
  Image image_;
  std::vector<std::pair<std::string, Image>> passes_;  // of image_ (settings_.passes)
  int samples_done_ = 0;
  uint64_t version_ = 0;
  std::string error_;
};

}  // namespace torrance
