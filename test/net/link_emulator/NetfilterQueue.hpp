// One NFQUEUE queue of the current network namespace, bound through libnetfilter_queue: the
// kernel hands each queued packet's id to a handler, and the packet waits in the kernel until
// accept() or drop() gives its verdict (in any order, at any later time). The queue does not
// fail open: when it is full the kernel drops the packet and counts it (overflow_drops).
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>

struct nfq_handle;
struct nfq_q_handle;
struct nfq_data;
struct nfgenmsg;

namespace uavslam::net {

struct QueueDrops {
  std::uint64_t queue_full = 0;   // the kernel dropped a packet because the queue was full
  std::uint64_t undelivered = 0;  // the kernel could not pass a packet to us (socket buffer full)
};

class NetfilterQueue {
 public:
  // Returns true when it keeps the packet (its verdict comes later through accept or drop), false
  // to drop it at once. `packet`/`length`: the IP packet when the queue copies packets, else
  // nullptr and 0.
  using PacketHandler =
      std::function<bool(std::uint32_t packet_id, const std::uint8_t* packet, std::size_t length)>;

  // Binds queue `number`; throws std::runtime_error saying what failed (not root, queue taken).
  // `copy_packets`: the kernel copies each packet to us (to look into it), not only its id.
  NetfilterQueue(std::uint16_t number, std::uint32_t max_length, bool copy_packets,
                 PacketHandler on_packet);
  NetfilterQueue(const NetfilterQueue&) = delete;
  NetfilterQueue& operator=(const NetfilterQueue&) = delete;
  ~NetfilterQueue();

  // The descriptor to poll for queued packets.
  int fd() const { return fd_; }

  // Reads every message the kernel has ready and calls the handler once per packet.
  void receive();

  void accept(std::uint32_t packet_id);
  void drop(std::uint32_t packet_id);

  // The kernel's drop counters of this queue (/proc/net/netfilter/nfnetlink_queue).
  QueueDrops drops() const;

 private:
  static int on_message(nfq_q_handle* queue, nfgenmsg* message, nfq_data* packet, void* self);

  std::uint16_t number_;
  PacketHandler on_packet_;
  nfq_handle* library_ = nullptr;
  nfq_q_handle* queue_ = nullptr;
  int fd_ = -1;
};

}  // namespace uavslam::net
