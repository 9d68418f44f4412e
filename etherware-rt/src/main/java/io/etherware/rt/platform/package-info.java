/**
 * The OS's real-time features through the Foreign Function &amp; Memory API: thread policy and
 * priority (SCHED_FIFO, SCHED_RR, SCHED_OTHER), CPU affinity, memory locking, each read back from
 * the OS, with a once-per-kind warning and a fix when refused. {@link
 * io.etherware.rt.platform.Platform} is the entry point; {@link
 * io.etherware.rt.platform.PlatformReport} is what a node prints at start.
 */
package io.etherware.rt.platform;
