// Ctrl-C (SIGINT) and SIGTERM ask a long run to stop at the next scan and keep what it has.
#pragma once

namespace uavslam::cli {

void install_stop_handler();
bool stop_requested();

}  // namespace uavslam::cli
