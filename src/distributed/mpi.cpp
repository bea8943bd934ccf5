#include "spp/distributed/mpi.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <cstring>
#include <exception>
#include <mutex>
#include <stdexcept>
#include <thread>

#include "spp/detail/dense_products.hpp"
#include "spp/distributed/window_work.hpp"
#include "spp/modal/modal.hpp"
#include "spp/detail/invalid.hpp"

namespace spp {

namespace {

// Tags: a worker's message to rank 0 (its last unit's output, or a failure, and a request for the next unit), and
// rank 0's answer (the next unit, or -1: no more), one reply tag per worker thread of a rank.
constexpr int kTagWork = 7001;
constexpr int kTagReplyBase = 7100;
constexpr int kMaxThreadsPerRank = 1024;  // reply tags 7100..8123 (MPI guarantees tags up to 32767)
// How long rank 0's main thread sleeps between two looks for messages: short against a unit (seconds), long enough
// that the polling thread costs no core.
constexpr auto kPollInterval = std::chrono::microseconds(200);

// The header of a worker's message: slot (its thread on its rank), unit (-1: none yet), failed (0/1); then the output
// (or the failure's message).
struct Header {
  std::int64_t slot, unit, failed;
};

std::string pack(const Header& h, const std::string& payload) {
  std::string m(sizeof(Header), '\0');
  std::memcpy(m.data(), &h, sizeof(Header));
  return m + payload;
}

int rank_of(MPI_Comm comm) {
  int r = 0;
  MPI_Comm_rank(comm, &r);
  return r;
}

int size_of(MPI_Comm comm) {
  int s = 0;
  MPI_Comm_size(comm, &s);
  return s;
}

void check_thread_level(int threads) {
  int level = MPI_THREAD_SINGLE;
  MPI_Query_thread(&level);
  if (level < MPI_THREAD_FUNNELED)
    detail::invalid(
        "spp on MPI: MPI was initialised with MPI_THREAD_SINGLE; initialise it with "
        "MPI_Init_thread and at least MPI_THREAD_FUNNELED (spp-mpi does)");
  if (threads > 1 && level < MPI_THREAD_SERIALIZED)
    detail::invalid("spp on MPI: " + std::to_string(threads) +
                                " threads per rank need MPI_THREAD_SERIALIZED, MPI gave only MPI_THREAD_FUNNELED: "
                                "use one thread per rank (--threads 1) and more ranks");
}

// Rank 0 tells every rank whether a unit failed, and the message; every rank then throws.
void agree_on_failure(MPI_Comm comm, std::string message, std::exception_ptr local) {
  int failed = message.empty() ? 0 : 1;
  MPI_Bcast(&failed, 1, MPI_INT, 0, comm);
  if (!failed) return;
  std::int64_t n = static_cast<std::int64_t>(message.size());
  MPI_Bcast(&n, 1, MPI_INT64_T, 0, comm);
  message.resize(static_cast<size_t>(n));
  MPI_Bcast(message.data(), static_cast<int>(n), MPI_CHAR, 0, comm);
  if (local) std::rethrow_exception(local);
  throw std::runtime_error(message);
}

}  // namespace

int threads_per_rank(MPI_Comm comm, int requested) {
  MPI_Comm node;
  MPI_Comm_split_type(comm, MPI_COMM_TYPE_SHARED, rank_of(comm), MPI_INFO_NULL, &node);
  const int local = size_of(node);
  MPI_Comm_free(&node);
  if (requested > 0) return requested;
  const int hw = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  return std::max(1, hw / std::max(1, local));
}

std::vector<std::string> distribute_units(MPI_Comm comm, size_t units, const std::vector<size_t>& order, int threads,
                                          const std::function<std::string(size_t)>& work) {
  {
    std::vector<char> seen(units, 0);
    bool ok = order.size() == units;
    for (size_t j : order) ok = ok && j < units && !seen[j]++;
    if (!ok) detail::invalid("distribute_units: the order is not a permutation of the units");
  }
  if (threads < 1 || threads > kMaxThreadsPerRank)
    detail::invalid("distribute_units: threads per rank must be in [1, " +
                                std::to_string(kMaxThreadsPerRank) + "], got " + std::to_string(threads));
  check_thread_level(threads);
  const int rank = rank_of(comm), size = size_of(comm);
  // rank 0 learns how many workers will ask it for units
  std::vector<int> counts(static_cast<size_t>(size), 0);
  MPI_Gather(&threads, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, comm);

  if (rank != 0) {
    std::mutex mpi_lock;  // MPI_THREAD_SERIALIZED: one call at a time
    auto worker = [&](int slot) {
      Header h{slot, -1, 0};
      std::string payload;
      for (;;) {
        const std::string m = pack(h, payload);
        std::int64_t next = -1;
        {
          const std::lock_guard<std::mutex> lock(mpi_lock);
          MPI_Send(m.data(), static_cast<int>(m.size()), MPI_BYTE, 0, kTagWork, comm);
          MPI_Recv(&next, 1, MPI_INT64_T, 0, kTagReplyBase + slot, comm, MPI_STATUS_IGNORE);
        }
        if (next < 0) return;
        h.unit = next;
        try {
          payload = work(static_cast<size_t>(next));
          h.failed = 0;
        } catch (const std::exception& e) {
          payload = "rank " + std::to_string(rank) + ": " + e.what();
          h.failed = 1;
        } catch (...) {
          payload = "rank " + std::to_string(rank) + ": an unknown exception";
          h.failed = 1;
        }
      }
    };
    std::vector<std::thread> pool;
    for (int t = 1; t < threads; ++t) pool.emplace_back(worker, t);
    worker(0);
    for (auto& th : pool) th.join();
    agree_on_failure(comm, "", nullptr);  // the message comes from rank 0
    return {};
  }

  // rank 0: local workers take units from the same queue its main thread hands out to the others
  std::vector<std::string> outputs(units);
  std::atomic<size_t> next{0};
  std::atomic<bool> stop{false};
  std::mutex failure_lock;
  std::string failure;
  std::exception_ptr local;
  auto take = [&]() -> std::int64_t {
    if (stop) return -1;
    const size_t k = next++;
    return k < units ? static_cast<std::int64_t>(order[k]) : -1;
  };
  auto fail = [&](const std::string& message, std::exception_ptr e) {
    const std::lock_guard<std::mutex> lock(failure_lock);
    if (failure.empty()) {
      failure = message;
      local = e;
    }
    stop = true;
  };
  auto local_worker = [&] {
    for (std::int64_t j = take(); j >= 0; j = take()) {
      try {
        outputs[static_cast<size_t>(j)] = work(static_cast<size_t>(j));
      } catch (const std::exception& e) {
        fail(std::string("rank 0: ") + e.what(), std::current_exception());
      } catch (...) {
        fail("rank 0: an unknown exception", std::current_exception());
      }
    }
  };
  std::vector<std::thread> pool;
  for (int t = 0; t < threads; ++t) pool.emplace_back(local_worker);
  long remote = 0;
  for (int r = 1; r < size; ++r) remote += counts[static_cast<size_t>(r)];
  std::string buffer;
  for (long done = 0; done < remote;) {
    int flag = 0;
    MPI_Status status;
    MPI_Iprobe(MPI_ANY_SOURCE, kTagWork, comm, &flag, &status);
    if (!flag) {
      std::this_thread::sleep_for(kPollInterval);
      continue;
    }
    int bytes = 0;
    MPI_Get_count(&status, MPI_BYTE, &bytes);
    buffer.resize(static_cast<size_t>(bytes));
    MPI_Recv(buffer.data(), bytes, MPI_BYTE, status.MPI_SOURCE, kTagWork, comm, MPI_STATUS_IGNORE);
    Header h;
    std::memcpy(&h, buffer.data(), sizeof(Header));
    if (h.unit >= 0) {
      if (h.failed)
        fail(buffer.substr(sizeof(Header)), nullptr);
      else
        outputs[static_cast<size_t>(h.unit)] = buffer.substr(sizeof(Header));
    }
    const std::int64_t reply = take();
    MPI_Send(&reply, 1, MPI_INT64_T, status.MPI_SOURCE, kTagReplyBase + static_cast<int>(h.slot), comm);
    if (reply < 0) ++done;
  }
  for (auto& th : pool) th.join();
  agree_on_failure(comm, failure, local);
  return outputs;
}

SolveResult solve_mpi(const System& system, const ModalForm& modal, const SolveOptions& options, MPI_Comm comm) {
  // OpenBLAS on one thread: its rounding depends on its thread count, and the workers are the parallelism
  const detail::SingleThreadedBlas single_threaded_blas;
  const WindowWork work(system, modal, options);
  const size_t n = work.units();
  // The costliest units first (largest-first keeps the tail short: the last unit handed out is a cheap one), by
  // WindowWork::unit_cost; ties in strip order.
  std::vector<size_t> order(n);
  for (size_t j = 0; j < n; ++j) order[j] = j;
  std::stable_sort(order.begin(), order.end(),
                   [&](size_t a, size_t b) { return work.unit_cost(a) > work.unit_cost(b); });
  const int threads = std::min<int>(threads_per_rank(comm, options.threads), static_cast<int>(std::max<size_t>(1, n)));
  const std::vector<std::string> outputs =
      distribute_units(comm, n, order, threads, [&](size_t j) { return work.trace_unit(j); });
  if (rank_of(comm) != 0) return {};
  return work.finish(outputs);
}

std::vector<SweepItemOutcome> run_sweep_mpi(const Sweep& sweep, const SolveOptions& options, MPI_Comm comm) {
  options.validate();
  const detail::SingleThreadedBlas single_threaded_blas;
  SolveOptions o = options;
  o.threads = threads_per_rank(comm, options.threads);
  o.progress = nullptr;
  const size_t n = sweep.items().size();
  std::vector<size_t> order(n);
  for (size_t j = 0; j < n; ++j) order[j] = j;
  // one item at a time per rank; an item's outcome travels as one byte of status and its message
  const std::vector<std::string> outputs = distribute_units(comm, n, order, 1, [&](size_t i) {
    const SweepItemOutcome r = run_sweep_item(sweep, i, o);
    return std::string(1, static_cast<char>(r.status)) + r.message;
  });
  if (rank_of(comm) != 0) return {};
  std::vector<SweepItemOutcome> outcomes(n);
  for (size_t i = 0; i < n; ++i) {
    outcomes[i].status = static_cast<SweepItemStatus>(outputs[i].at(0));
    outcomes[i].message = outputs[i].substr(1);
  }
  return outcomes;
}

}  // namespace spp
