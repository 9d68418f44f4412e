/**
 * The pendulum's Etherware components (paper Section VI-A and VI-C, Fig. 8 and 10): the
 * {@link io.etherware.pendulum.components.DspProxy}, which owns the serial link to the DSP board
 * on its node, and the {@link io.etherware.pendulum.components.PendulumController}, which at each
 * Tick requests the joint angles from the proxy, computes the torque and sends it back.
 *
 * <p>The messages they exchange and the controller's state are records registered by
 * {@link io.etherware.pendulum.components.PendulumContents#register()}, so they travel as XML
 * between nodes and an upgrade or a migration can carry the controller's state.
 */
package io.etherware.pendulum.components;
