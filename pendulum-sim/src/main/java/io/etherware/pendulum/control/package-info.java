/**
 * Controller design and the per-cycle control computation for the pendulum, independent of the
 * middleware: pole placement (Ackermann), zero-order-hold discretization and loop analysis, the
 * velocity estimator and the saturated state-feedback law, with their memory in plain records.
 */
package io.etherware.pendulum.control;
