// Ctrl-C (SIGINT) and SIGTERM ask a process to stop: loops check stop_requested() and end
// cleanly, flushing what they have.
#pragma once

namespace uavslam::process {

void install_stop_handler();
bool stop_requested();

}  // namespace uavslam::process
