// Test helper: the message of the phongsim::Error a callable throws.
#pragma once

#include <gtest/gtest.h>

#include <exception>
#include <string>

#include "base/error.h"

namespace phongsim::testing {

// The message of the Error `f` throws; fails the test when it throws nothing or something else.
template <class F>
std::string ErrorOf(F&& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "not a phongsim::Error: " << e.what();
    return "";
  }
  ADD_FAILURE() << "no error";
  return "";
}

}  // namespace phongsim::testing
