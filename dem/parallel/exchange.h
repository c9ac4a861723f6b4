#pragma once
// Point-to-point plumbing of the three-stage (x, then y, then z) exchange: along one
// axis, every rank sends one buffer to each face neighbour and receives one from each,
// with MPI_Isend/MPI_Irecv and one MPI_Waitall. Buffers are the caller's and keep their
// capacity between calls, so the per-step refresh allocates nothing after warm-up.
#include <mpi.h>

#include <array>
#include <exception>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include "dem/core/error.h"
#include "dem/parallel/fixed_point_sum.h"

namespace upgrain::dem {

// Sends to_side[s] to neighbour[s] and receives from_side[s] from it (s = 0 lower, 1
// upper face). With counts_known the receive buffers already have their sizes (a ghost
// refresh); otherwise the counts are exchanged first. A message carries the side it was sent
// towards in its tag (tag .. tag + 3), so that the two messages between the same two ranks are
// told apart: along a periodic axis of two blocks both neighbours are one rank, and of one
// block, the rank itself.
template <class T>
void exchange_along_axis(MPI_Comm comm, const std::array<int, 2>& neighbor,
                         const std::array<std::vector<T>, 2>& to_side,
                         std::array<std::vector<T>, 2>& from_side, bool counts_known, int tag) {
  std::array<MPI_Request, 4> req{};
  if (!counts_known) {
    std::array<long, 2> send_count{static_cast<long>(to_side[0].size()),
                                   static_cast<long>(to_side[1].size())};
    std::array<long, 2> recv_count{0, 0};
    for (int s = 0; s < 2; ++s) {
      MPI_Irecv(&recv_count[s], 1, MPI_LONG, neighbor[s], tag + 1 - s, comm, &req[s]);
      MPI_Isend(&send_count[s], 1, MPI_LONG, neighbor[s], tag + s, comm, &req[2 + s]);
    }
    MPI_Waitall(4, req.data(), MPI_STATUSES_IGNORE);
    for (int s = 0; s < 2; ++s) from_side[s].resize(static_cast<std::size_t>(recv_count[s]));
  }
  for (int s = 0; s < 2; ++s) {
    const std::size_t bytes_in = from_side[s].size() * sizeof(T);
    const std::size_t bytes_out = to_side[s].size() * sizeof(T);
    if (bytes_in > 2147483647u || bytes_out > 2147483647u)
      throw Error("parallel exchange: message above 2 GB");
    MPI_Irecv(from_side[s].data(), static_cast<int>(bytes_in), MPI_BYTE, neighbor[s], tag + 3 - s, comm,
              &req[s]);
    MPI_Isend(to_side[s].data(), static_cast<int>(bytes_out), MPI_BYTE, neighbor[s], tag + 2 + s, comm,
              &req[2 + s]);
  }
  MPI_Waitall(4, req.data(), MPI_STATUSES_IGNORE);
}

// Gathers every rank's records on `root` (rank order; empty elsewhere), as bytes. For
// output-time reductions: the caller sorts by a global key and sums in that order, so the
// result does not depend on how the records were divided among the ranks.
template <class T>
std::vector<T> gather_to_root(const std::vector<T>& mine, MPI_Comm comm, int root = 0) {
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  if (mine.size() * sizeof(T) > 2147483647u) throw Error("parallel gather: message above 2 GB");
  const int bytes = static_cast<int>(mine.size() * sizeof(T));
  std::vector<int> counts(rank == root ? size : 0), displs(rank == root ? size : 0);
  MPI_Gather(&bytes, 1, MPI_INT, counts.data(), 1, MPI_INT, root, comm);
  std::vector<T> all;
  if (rank == root) {
    long total = 0;
    for (int r = 0; r < size; ++r) {
      displs[r] = static_cast<int>(total);
      total += counts[r];
    }
    if (total > 2147483647L) throw Error("parallel gather: message above 2 GB");
    all.resize(static_cast<std::size_t>(total) / sizeof(T));
  }
  MPI_Gatherv(mine.data(), bytes, MPI_BYTE, all.data(), counts.data(), displs.data(), MPI_BYTE, root, comm);
  return all;
}

// The rows of an id-sorted whole of `total` records split evenly over `size` ranks: rank r
// holds rows [first_row(total, r, size), first_row(total, r + 1, size)).
inline long first_row(long total, int rank, int size) {
  return static_cast<long>(static_cast<long long>(total) * rank / size);
}
// The rank whose rows hold row `row` (the largest r with first_row(r) <= row); a row outside
// [0, total) goes to the first or the last rank (whose check then finds it out of place).
inline int row_owner(long row, long total, int size) {
  if (total <= 0 || row < 0) return 0;
  if (row >= total) return size - 1;
  return static_cast<int>(((static_cast<long long>(row) + 1) * size - 1) / total);
}

// Sends every record of `mine` to rank destination(record) and returns what this rank
// received, by sending rank (each rank's records in their order in `mine`): one MPI_Alltoall
// of the counts and one MPI_Alltoallv of the records, as bytes. Collective.
template <class T, class Destination>
std::vector<T> send_to_ranks(const std::vector<T>& mine, MPI_Comm comm, Destination destination) {
  int size = 1;
  MPI_Comm_size(comm, &size);
  std::vector<int> to(mine.size());
  std::vector<long> count(static_cast<std::size_t>(size), 0);
  for (std::size_t k = 0; k < mine.size(); ++k)
    ++count[static_cast<std::size_t>(to[k] = destination(mine[k]))];
  std::vector<int> send_bytes(static_cast<std::size_t>(size)), send_at(static_cast<std::size_t>(size));
  std::vector<long> next(static_cast<std::size_t>(size));
  long at = 0;
  for (std::size_t r = 0; r < count.size(); ++r) {
    if (count[r] * static_cast<long>(sizeof(T)) > 2147483647L ||
        at * static_cast<long>(sizeof(T)) > 2147483647L)
      throw Error("parallel exchange: message above 2 GB");
    send_bytes[r] = static_cast<int>(count[r] * static_cast<long>(sizeof(T)));
    send_at[r] = static_cast<int>(at * static_cast<long>(sizeof(T)));
    next[r] = at;
    at += count[r];
  }
  std::vector<T> out(mine.size());
  for (std::size_t k = 0; k < mine.size(); ++k)
    out[static_cast<std::size_t>(next[static_cast<std::size_t>(to[k])]++)] = mine[k];
  std::vector<int> recv_bytes(static_cast<std::size_t>(size)), recv_at(static_cast<std::size_t>(size));
  MPI_Alltoall(send_bytes.data(), 1, MPI_INT, recv_bytes.data(), 1, MPI_INT, comm);
  long total = 0;
  for (std::size_t r = 0; r < recv_bytes.size(); ++r) {
    recv_at[r] = static_cast<int>(total);
    total += recv_bytes[r];
    if (total > 2147483647L) throw Error("parallel exchange: message above 2 GB");
  }
  std::vector<T> in(static_cast<std::size_t>(total) / sizeof(T));
  MPI_Alltoallv(out.data(), send_bytes.data(), send_at.data(), MPI_BYTE, in.data(), recv_bytes.data(),
                recv_at.data(), MPI_BYTE, comm);
  return in;
}

// Makes an error collective: every rank calls it; if any rank passes a non-empty message,
// the lowest such rank's message is thrown as upgrain::CollectiveError on every rank, so no
// rank is left waiting in a later message and the driver prints it once.
inline void throw_if_any(MPI_Comm comm, const std::string& local_message) {
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  int mine = local_message.empty() ? size : rank;
  int first = size;
  MPI_Allreduce(&mine, &first, 1, MPI_INT, MPI_MIN, comm);
  if (first == size) return;
  std::string m = local_message;
  int length = static_cast<int>(m.size());
  MPI_Bcast(&length, 1, MPI_INT, first, comm);
  m.resize(static_cast<std::size_t>(length));
  MPI_Bcast(m.data(), length, MPI_CHAR, first, comm);
  throw CollectiveError(m);
}

// Collective: runs `work` on `root`; an exception there is thrown as upgrain::CollectiveError on
// every rank, so no rank waits forever in a later message.
inline void run_on_root(MPI_Comm comm, const std::function<void()>& work, int root = 0) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  std::string error;
  if (rank == root) {
    try {
      work();
    } catch (const std::exception& e) {
      error = e.what();
      if (error.empty()) error = "unknown error";
    }
  }
  throw_if_any(comm, error);
}

// Collective: the sums of every quantity over all ranks, the same bits on every rank and
// on any partition of the terms (fixed_point_sum.h).
inline std::vector<double> global_sums(FixedPointSums& sums, MPI_Comm comm) {
  std::vector<std::int64_t>& l = sums.limbs();
  MPI_Allreduce(MPI_IN_PLACE, l.data(), static_cast<int>(l.size()), MPI_INT64_T, MPI_SUM, comm);
  return sums.values();
}

}  // namespace upgrain::dem
