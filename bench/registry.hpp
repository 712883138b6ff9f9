#pragma once
// The benchmark groups; each file registers its own (bench_main.cpp calls them
// after reading the thread counts).
namespace mpsolid::bench {

void register_step_benchmarks();       // bench_step.cpp
void register_kernel_benchmarks();     // bench_kernels.cpp
void register_skip_work_benchmarks();  // bench_skip_work.cpp
void register_neighbor_benchmarks();   // bench_neighbors.cpp
void register_contact_benchmarks();    // bench_contact.cpp
void register_team_benchmarks();       // bench_team.cpp
void register_gas_benchmarks();        // bench_gas.cpp
void register_space_benchmarks();      // bench_space.cpp

}  // namespace mpsolid::bench
