#include "app/program_error.h"

#include <cstdio>

namespace app {

int ErrorReporter::operator()(std::string_view message) const {
  std::fprintf(stderr, "%.*s: error: %.*s\n", static_cast<int>(program.size()), program.data(),
               static_cast<int>(message.size()), message.data());
  return 1;
}

}  // namespace app
