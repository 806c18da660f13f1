#include "common/StopRequest.hpp"

#include <csignal>

namespace uavslam::process {
namespace {

volatile std::sig_atomic_t g_stop = 0;

extern "C" void request_stop(int) {
  g_stop = 1;
}

}  // namespace

void install_stop_handler() {
  std::signal(SIGINT, request_stop);
  std::signal(SIGTERM, request_stop);
}

bool stop_requested() {
  return g_stop != 0;
}

}  // namespace uavslam::process
