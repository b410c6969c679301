// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// What a call throws, for the tests of error messages.
#include "section/error.h"

#include <string>

/// The message of the section::Error that `f()` throws, or "no error".
template <class F>
std::string thrown(F&& f) {
  try {
    f();
  } catch (const section::Error& e) {
    return e.what();
  }
  return "no error";
}
