/**
 * Latency distributions in nanoseconds: {@link io.etherware.rt.stats.LatencyRecorder} records them
 * on one thread without locks or allocation, {@link io.etherware.rt.stats.LatencySnapshot} is what
 * readers get back. The scheduler's and the Notifier's statistics hand out snapshots; the
 * histogram library behind them is not part of this API.
 */
package io.etherware.rt.stats;
