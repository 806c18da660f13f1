// A serial device (a USB CDC-ACM sensor, a USB-UART to an autopilot's TELEM port, or a
// pseudo-terminal in tests) opened for a binary protocol: raw mode (no echo, no line editing, no
// CR/LF translation), 8N1, no flow control, reads that never block. Shared by the SCIP 2.0 and
// MAVLink links.
#pragma once

#include <string>

namespace uavslam::drivers {

// The open descriptor (the caller closes it). Throws std::system_error naming the device when it
// cannot be opened or is not a tty, and std::invalid_argument for a baud rate termios lacks.
int open_raw_serial(const std::string& device, int baud);

}  // namespace uavslam::drivers
