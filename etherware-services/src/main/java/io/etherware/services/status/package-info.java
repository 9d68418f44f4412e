/**
 * A node's status, for operators and tools: {@link io.etherware.services.status.Status#snapshot}
 * reads its components, dispatchers' latency and deadline misses, network peers with their clock
 * offsets, and counters; a {@link io.etherware.services.status.StatusService} answers other nodes'
 * {@link io.etherware.services.status.StatusRequest}s with it (the control tool's source).
 */
package io.etherware.services.status;
