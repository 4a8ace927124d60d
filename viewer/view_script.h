#pragma once
// A script of mouse events and steps played through `kerf view`'s window
// instead of a person (tests, recorded demonstrations), one command a line:
//   steps N             the session stepped N times, then drawn
//   press X Y           the left button pressed at (X, Y): fractions of the
//   move X Y            window's width and height from its lower left corner
//   release X Y
//   screenshot FILE     the window as drawn, to a PNG (relative to the script's folder)
// '#' starts a comment. The mouse events go through the window's interactor,
// as a person's do.
#include <string>

#include "viewer/view_window.h"

namespace kerf {

/// Plays `path` on `window`; throws naming the script's file and line on a line it cannot read.
void play_view_script(const std::string& path, ViewWindow& window);

}  // namespace kerf
