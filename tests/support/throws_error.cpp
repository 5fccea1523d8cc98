#include "support/throws_error.hpp"

namespace finflex::test {

::testing::AssertionResult ThrowsError(const std::function<void()>& action, ErrorCode code,
                                       const std::string& field_part,
                                       const std::vector<std::string>& message_parts) {
  try {
    action();
  } catch (const Error& e) {
    if (e.code() != code) {
      return ::testing::AssertionFailure()
             << "code " << error_code_name(e.code()) << " instead of " << error_code_name(code)
             << " (field '" << e.field() << "': " << e.what() << ")";
    }
    if (e.field().find(field_part) == std::string::npos) {
      return ::testing::AssertionFailure()
             << "field '" << e.field() << "' lacks '" << field_part << "': " << e.what();
    }
    for (const std::string& part : message_parts) {
      if (std::string(e.what()).find(part) == std::string::npos) {
        return ::testing::AssertionFailure() << "message lacks '" << part << "': " << e.what();
      }
    }
    return ::testing::AssertionSuccess() << e.what();
  } catch (const std::exception& e) {
    return ::testing::AssertionFailure() << "not a finflex::Error: " << e.what();
  }
  return ::testing::AssertionFailure() << "nothing thrown";
}

}  // namespace finflex::test
