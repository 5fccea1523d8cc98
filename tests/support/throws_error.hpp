// A GoogleTest predicate for FinFlex's errors: the code, the field and the message.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "finflex/error.hpp"

namespace finflex::test {

// Success iff `action` throws finflex::Error with `code`, a field containing
// `field_part` and a message containing every one of `message_parts`.
::testing::AssertionResult ThrowsError(const std::function<void()>& action, ErrorCode code,
                                       const std::string& field_part,
                                       const std::vector<std::string>& message_parts = {});

// The same with one message part.
inline ::testing::AssertionResult ThrowsError(const std::function<void()>& action, ErrorCode code,
                                              const std::string& field_part,
                                              const std::string& message_part) {
  return ThrowsError(action, code, field_part, std::vector<std::string>{message_part});
}

}  // namespace finflex::test
