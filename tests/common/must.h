// must(): a Result's value in a test, where an Error means the test itself
// cannot go on (a frame that should render, an image that should be read).
// Guarantees: on an Error the test fails with the Error's text and its body
// ends (the exception GoogleTest reports); never returns a default value.
// Never: used for the Error a test expects (check ok() and error() there).
#pragma once
#include <stdexcept>
#include <utility>

#include <gtest/gtest.h>

#include "study/common/error.h"

namespace dtlab::test {

template <class T>
T must(Result<T> r) {
  if (!r) {
    ADD_FAILURE() << "unexpected Error: " << r.error().to_string();
    throw std::runtime_error("must(): " + r.error().to_string());
  }
  return std::move(r).value();
}

}  // namespace dtlab::test
