#pragma once
// What the viewer reacts to, whether it comes from the window (GLFW callbacks) or from a script
// (--script FILE, for tests and demos): both feed the same queue, so a script exercises exactly
// the code a user's input does.
//
// Script lines (one event each; '#' starts a comment):
//   frames N            render and present N frames before the next line
//   key NAME            a key press: 1-5 (method), shift+1 .. shift+5 (the split's other method),
//                       v (split view), g (next view), f1-f6 (a view), p (save EXR + PNG),
//                       r (reset the camera), w a s d q e (fly a step), escape or esc (quit);
//                       names in any case (V, F1, Esc as the README writes them)
//   drag left|right DX DY   a mouse drag (left: orbit; right: pan), in window pixels
//   scroll DY           the wheel (positive: zoom in)
//   resize W H          resize the window
//   screenshot FILE.png the window's current contents
//   quit
#include <deque>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

namespace mixtrace {

struct InputEvent {
  enum class Kind { Frames, Key, Drag, Scroll, Resize, Screenshot, Quit };
  Kind kind = Kind::Frames;
  std::string name;    // Key: key name; Screenshot: file; Drag: button ("left" or "right")
  float x = 0.0f, y = 0.0f;   // Drag: dx, dy; Scroll: dy; Resize: width, height; Frames: count
};

// Parses a script; throws Error naming the line for anything it does not understand.
std::deque<InputEvent> parseInputScript(const std::string& text, const std::string& fileName);
std::deque<InputEvent> loadInputScript(const std::string& path);

// The key names a script (and the window) may use, in their canonical (lower-case) form.
const std::vector<std::string>& knownKeyNames();

// A key name as a user writes it ("V", "F1", "Esc", "Shift+2") in its canonical form ("v", "f1",
// "escape", "shift+2"): any case, and "esc" for "escape". Throws Error listing the valid names.
std::string canonicalKeyName(const std::string& written);

// The fly keys' directions in camera space (x right, y up, z forward): w s forward/back, d a
// right/left, e q up/down; zero for any other key. Held keys and scripted presses alike.
glm::vec3 flyDirectionOf(const std::string& key);

}  // namespace mixtrace
