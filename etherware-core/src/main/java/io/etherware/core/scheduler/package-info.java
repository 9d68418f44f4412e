/**
 * The scheduler SPI between the kernel and its dispatchers, and {@link
 * io.etherware.core.scheduler.FifoScheduler}, the original Etherware's single FIFO dispatcher.
 */
package io.etherware.core.scheduler;
