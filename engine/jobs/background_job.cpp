#include "engine/jobs/background_job.h"

#include <new>

#include "engine/util/error.h"

namespace strata {

std::string jobErrorText(std::exception_ptr e, const std::string& outOfMemoryAdvice) {
  try {
    std::rethrow_exception(e);
  } catch (const Cancelled&) {
    return "cancelled";
  } catch (const Error& error) {
    return error.what();
  } catch (const std::bad_alloc&) {
    return "out of memory" + outOfMemoryAdvice;
  } catch (const std::exception& error) {
    return std::string("unexpected error: ") + error.what();
  } catch (...) {
    return "unexpected error";
  }
}

}  // namespace strata
