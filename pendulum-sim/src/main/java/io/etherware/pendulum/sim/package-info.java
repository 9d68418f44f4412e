/** Simulated time for deterministic lock-step runs of the board, the link and a controller. */
package io.etherware.pendulum.sim;
