#include "viewer/viewer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <deque>
#include <filesystem>
#include <map>
#include <memory>

#include "cms/methods.h"
#include "session/default_scene.h"
#include "session/method_setup.h"
#include "session/output_plan.h"
#include "session/sample_loop.h"
#include "session/scene_camera.h"
#include "output/png_preview.h"
#include "output/render_output.h"
#include "wavefront/wavefront_renderer.h"
#include "scene/prepared_scene.h"
#include "shared/display.h"
#include "util/error.h"
#include "util/log.h"
#include "util/timing.h"
#include "viewer/camera_controller.h"
#include "viewer/display_pass.h"
#include "viewer/input.h"
#include "viewer/swapchain.h"
#include "viewer/window.h"
#include "vulkan/buffer.h"
#include "vulkan/check.h"
#include "vulkan/context.h"
#include "vulkan/pipeline.h"

namespace mixtrace {
namespace {

const char* const kViewNames[shared::kViewCount] = {"image", "variance", "cells", "alpha sum", "likely light",
                                                    "cell samples"};
constexpr double kFrameBudgetSeconds = 1.0 / 15.0;   // rendering per frame, so input stays responsive
constexpr float kScriptFlySeconds = 0.1f;            // one scripted W/A/S/D/Q/E press

// The split view's right-hand method where none was chosen: plain MIS, or for plain MIS itself
// the default method (cms/methods.h).
std::string splitPartnerOf(const std::string& method) {
  return method == kPlainMisMethod ? kDefaultMethod : kPlainMisMethod;
}

// One method's renderer and the display pass over its state. The prepared scene is the viewer's,
// shared by every method: a method's own part is its settings and light tables.
struct MethodView {
  MethodSetup setup;
  std::unique_ptr<WavefrontRenderer> renderer;
  std::unique_ptr<DisplayPass> display;
  unsigned cameraVersion = ~0u;
  std::unique_ptr<SampleLoop> samples;   // since the last restart; its seconds() are the method's time
};

class Viewer {
 public:
  Viewer(const RenderOptions& o, const std::string& scriptPath);
  ~Viewer();
  int run();

 private:
  MethodView& view(const std::string& method);
  void handle(const InputEvent& e);
  void render();
  void present();
  void recreateDisplay();
  void screenshot(const std::string& path) const;
  void save();
  std::string title() const;
  std::vector<MethodView*> visible();

  RenderOptions options_;
  const PreparedScene prepared_;   // built once: switching methods builds no BVH
  std::string sceneName_;
  Window window_;
  VulkanContext ctx_;
  std::unique_ptr<Swapchain> swapchain_;
  std::unique_ptr<Buffer> display_;   // packed 8-bit pixels of the window
  std::map<std::string, std::unique_ptr<MethodView>> views_;
  std::unique_ptr<CameraController> camera_;
  std::deque<InputEvent> script_, events_;
  bool scripted_ = false, quit_ = false, split_ = false;
  std::string method_, other_ = kPlainMisMethod;
  uint32_t viewMode_ = shared::kViewImage;
  int framesLeft_ = 0;
  uint64_t frames_ = 0;
};

// The window starts at a whole multiple of the film's size, at least about 640 pixels wide.
int windowScale(const RenderOptions& o) { return std::max(1, 640 / std::max(o.width, 1)); }

Viewer::Viewer(const RenderOptions& o, const std::string& scriptPath)
    : options_(o),
      prepared_(prepareScene(loadSceneForRendering(o.scene.empty() ? defaultScenePath() : o.scene, o))),
      window_(o.width * windowScale(o), o.height * windowScale(o), "mixtrace"),
      ctx_(ContextOptions{o.device, o.validation, window_.vulkanInstanceExtensions(),
                          [this](VkInstance instance) { return window_.createSurface(instance); }}),
      method_(o.method) {
  sceneName_ = prepared_.scene.name;
  if (!scriptPath.empty()) {
    script_ = loadInputScript(scriptPath);
    scripted_ = true;
  }
  if (other_ == method_) other_ = splitPartnerOf(method_);
  int w = 0, h = 0;
  window_.framebufferSize(w, h);
  swapchain_ = std::make_unique<Swapchain>(ctx_, uint32_t(std::max(w, 1)), uint32_t(std::max(h, 1)));
  view(method_);
  const Scene& scene = prepared_.scene;
  camera_ = std::make_unique<CameraController>(makeCamera(scene, uint32_t(o.width), uint32_t(o.height)),
                                               scene.bounds.center(), glm::length(scene.bounds.extent()));
  recreateDisplay();
  info("view " + sceneName_ + " on " + ctx_.deviceName() +
       ": keys " + viewerKeyRange() + " method, shift+" + viewerKeyRange() +
       " and V split view, G or F1-F6 debug views, mouse orbit/pan/zoom, WASDQE fly, P save, R reset camera, Esc quit");
}

Viewer::~Viewer() { vkDeviceWaitIdle(ctx_.device()); }

MethodView& Viewer::view(const std::string& method) {
  auto found = views_.find(method);
  if (found != views_.end()) return *found->second;
  auto v = std::make_unique<MethodView>();
  v->setup = setUpMethod(prepared_, options_, method);
  v->renderer = std::make_unique<WavefrontRenderer>(ctx_, prepared_, v->setup.lights, v->setup.settings);
  v->display = std::make_unique<DisplayPass>(ctx_, *v->renderer);
  if (display_) v->display->bindWindow(*display_);
  return *views_.emplace(method, std::move(v)).first->second;
}

std::vector<MethodView*> Viewer::visible() {
  std::vector<MethodView*> v{&view(method_)};
  if (split_) v.push_back(&view(other_));
  return v;
}

void Viewer::recreateDisplay() {
  vkCheck(vkDeviceWaitIdle(ctx_.device()), "vkDeviceWaitIdle");
  const VkExtent2D e = swapchain_->extent();
  display_ = std::make_unique<Buffer>(ctx_, VkDeviceSize(e.width) * e.height * sizeof(uint32_t), "display", true);
  for (auto& [method, v] : views_) v->display->bindWindow(*display_);
}

void Viewer::handle(const InputEvent& e) {
  using Kind = InputEvent::Kind;
  const bool wasSplit = split_;
  switch (e.kind) {
    case Kind::Frames: framesLeft_ = int(e.x); break;
    case Kind::Quit: quit_ = true; break;
    case Kind::Screenshot: screenshot(e.name); break;
    case Kind::Scroll: camera_->zoom(e.y); break;
    case Kind::Resize: window_.resize(int(e.x), int(e.y)); break;
    case Kind::Drag:
      if (e.name == "left") camera_->orbit(e.x, e.y);
      else {
        const VkExtent2D w = swapchain_->extent();
        const float filmHeight = float(options_.height);
        camera_->pan(e.x, e.y, shared::letterboxScale(w.width, w.height, uint32_t(options_.width), uint32_t(filmHeight)) *
                                   filmHeight);
      }
      break;
    case Kind::Key: {
      const std::string& k = e.name;
      // Method keys: the table's viewer keys (cms/methods.h); shift+key picks the split's other.
      const MethodInfo* keyed = k.size() == 1 ? methodForViewerKey(k[0]) : nullptr;
      if (keyed) {
        method_ = keyed->name;
        if (other_ == method_) other_ = splitPartnerOf(method_);
      } else if (k.rfind("shift+", 0) == 0) {
        const MethodInfo* right = methodForViewerKey(k.back());
        if (right && right->name != method_) {
          other_ = right->name;
          split_ = true;
        }
      } else if (k == "v") {
        split_ = !split_;
      } else if (k == "g") {
        viewMode_ = (viewMode_ + 1) % shared::kViewCount;
      } else if (k[0] == 'f' && k.size() == 2) {
        viewMode_ = uint32_t(k[1] - '1');
      } else if (k == "p") {
        save();
      } else if (k == "r") {
        camera_->reset();
      } else if (k == "escape") {
        quit_ = true;
      } else {   // a scripted fly step
        camera_->fly(flyDirectionOf(k), kScriptFlySeconds);
      }
      break;
    }
  }
  // A split view compares the two methods at equal time from the moment it opens.
  if (split_ && !wasSplit)
    for (MethodView* v : visible()) v->cameraVersion = ~0u;
}

void Viewer::render() {
  std::vector<MethodView*> shown = visible();
  for (MethodView* v : shown)
    if (v->cameraVersion != camera_->version()) {
      v->renderer->restart(camera_->camera());
      v->cameraVersion = camera_->version();
      // One batch per frame, sized to the frame budget, up to --spp (session/sample_loop.h).
      SampleTarget target;
      target.spp = options_.spp > 0 ? uint32_t(options_.spp) : 0;
      target.batchSeconds = kFrameBudgetSeconds;
      target.planTotal = false;
      v->samples = std::make_unique<SampleLoop>(*v->renderer, target);
    }
  // Equal time: of the methods shown, the one that has had less rendering time goes next.
  MethodView* next = shown[0];
  for (MethodView* v : shown)
    if (v->samples->seconds() < next->samples->seconds()) next = v;
  next->samples->step();
}

void Viewer::present() {
  const VkExtent2D e = swapchain_->extent();
  std::vector<MethodView*> shown = visible();
  const bool presented = swapchain_->present(*display_, [&](VkCommandBuffer cmd) {
    for (size_t i = 0; i < shown.size(); ++i) {
      MethodView& v = *shown[i];
      shared::DisplayConstants dc{};
      dc.windowWidth = e.width;
      dc.windowHeight = e.height;
      dc.filmWidth = uint32_t(options_.width);
      dc.filmHeight = uint32_t(options_.height);
      dc.xBegin = uint32_t(i * e.width / shown.size());
      dc.xEnd = uint32_t((i + 1) * e.width / shown.size());
      dc.view = viewMode_;
      dc.clusterCount = v.renderer->clusterCount();
      dc.exposure = 1.0f;
      dc.spp = v.renderer->samplesPerPixel();
      dc.divider = i > 0 ? 1u : 0u;
      dc.redFirst = swapchain_->redFirst() ? 1u : 0u;
      v.display->record(cmd, dc);
    }
  });
  if (!presented) {
    int w = 0, h = 0;
    window_.framebufferSize(w, h);
    swapchain_->recreate(uint32_t(std::max(w, 1)), uint32_t(std::max(h, 1)));
    recreateDisplay();
  }
}

void Viewer::screenshot(const std::string& path) const {
  const VkExtent2D e = swapchain_->extent();
  std::vector<uint32_t> packed(size_t(e.width) * e.height);
  display_->download(packed.data(), packed.size() * sizeof(uint32_t));
  std::vector<unsigned char> rgb(packed.size() * 3);
  const bool redFirst = swapchain_->redFirst();
  for (size_t i = 0; i < packed.size(); ++i) {
    const unsigned char a = packed[i] & 255u, b = (packed[i] >> 8) & 255u, c = (packed[i] >> 16) & 255u;
    rgb[3 * i + 0] = redFirst ? a : c;
    rgb[3 * i + 1] = b;
    rgb[3 * i + 2] = redFirst ? c : a;
  }
  writePng8(path, int(e.width), int(e.height), rgb);
  info("screenshot " + path + " (" + title() + ")");
}

void Viewer::save() {
  MethodView& v = view(method_);
  Image standardError;
  Image image = v.renderer->readImage(&standardError);
  namespace fs = std::filesystem;
  std::string path = options_.out;
  if (path.empty()) {
    const std::string stem = fs::path(sceneName_).stem().string() + "-" + method_;
    path = stem + ".exr";
    for (int i = 2; fs::exists(path); ++i) path = stem + "-" + std::to_string(i) + ".exr";
  }
  RenderOutputInfo written;
  written.method = method_;
  written.estimator = v.setup.estimator;
  written.scene = sceneName_;
  written.spp = int(v.renderer->samplesPerPixel());
  written.seconds = v.samples ? v.samples->seconds() : 0.0;
  writeRenderOutput(path, image, &standardError, written, options_.png);
  const std::string preview = previewPathFor(path, options_.png);
  info("saved " + path + (preview.empty() ? "" : " and " + preview) + " (" +
       std::to_string(v.renderer->samplesPerPixel()) + " spp)");
}

std::string Viewer::title() const {
  auto describe = [&](const std::string& method) {
    const MethodView& v = *views_.at(method);
    const uint32_t spp = v.renderer->samplesPerPixel();
    char b[160];
    const double seconds = v.samples ? v.samples->seconds() : 0.0;
    std::snprintf(b, sizeof(b), "%s: %u spp, %.1f s, %s samples/s", method.c_str(), spp, seconds,
                  formatRate(seconds > 0 ? spp * double(options_.width) * options_.height / seconds : 0.0).c_str());
    return std::string(b);
  };
  std::string t = "mixtrace - " + sceneName_ + " - " + describe(method_);
  if (split_ && views_.count(other_)) t += " | " + describe(other_) + " (split, equal time)";
  return t + " - view: " + kViewNames[viewMode_];
}

int Viewer::run() {
  while (!quit_) {
    // A script drives the viewer between its 'frames' lines; without one, the window does.
    while (scripted_ && framesLeft_ == 0 && !quit_) {
      if (script_.empty()) {
        quit_ = true;   // a script that ends without 'quit' still ends
        break;
      }
      InputEvent e = script_.front();
      script_.pop_front();
      handle(e);
    }
    if (quit_) break;
    window_.poll(events_);
    while (!events_.empty()) {
      handle(events_.front());
      events_.pop_front();
    }
    if (window_.closeRequested()) break;
    const auto frameStart = Clock::now();
    const glm::vec3 fly = window_.flyDirection();
    render();
    if (fly != glm::vec3(0.0f)) camera_->fly(fly, float(secondsSince(frameStart)));
    int w = 0, h = 0;
    window_.framebufferSize(w, h);
    if (w == 0 || h == 0) continue;   // minimised
    const VkExtent2D e = swapchain_->extent();
    if (uint32_t(w) != e.width || uint32_t(h) != e.height) {
      swapchain_->recreate(uint32_t(w), uint32_t(h));
      recreateDisplay();
    }
    present();
    window_.setTitle(title());
    ++frames_;
    if (framesLeft_ > 0) --framesLeft_;
  }
  vkCheck(vkDeviceWaitIdle(ctx_.device()), "vkDeviceWaitIdle");
  info("view: " + std::to_string(frames_) + " frames; " + title());
  if (options_.validation) {
    const uint32_t errors = ctx_.validationErrors();
    std::fprintf(stderr, "mixtrace: view: %u validation errors\n", errors);
    return errors > 0 ? 1 : 0;
  }
  return 0;
}

}  // namespace

int runViewer(const RenderOptions& options, const std::string& scriptPath) {
  setQuiet(options.quiet);
  if (options.backend != "vulkan") throw Error("view renders with the Vulkan backend only (drop --backend cpu)");
  // Where P saves, checked before the window opens rather than when the key is pressed.
  checkViewerOutputs(options, options.scene.empty() ? defaultScenePath() : options.scene);
  Viewer viewer(options, scriptPath);
  return viewer.run();
}

}  // namespace mixtrace
