/**
 * The pendulum's Etherware components (paper Section VI-A and VI-C, Fig. 8 and 10): the
 * {@link io.etherware.pendulum.components.DspProxy}, which owns the serial link to the DSP board
 * on its node, and the {@link io.etherware.pendulum.components.PendulumController}, which at each
 * Tick requests the joint angles from the proxy, computes the torque and sends it back.
 *
 * <pre>{@code
 * SimulatedSerialLink link = SimulatedSerialLink.realTime(SimulatedSerialLink.Config.defaults());
 * DspBoard board = new DspBoard(DspBoardConfig.defaults(), parameters, initial, link.boardEnd());
 * DspClient client = new DspClient(link.hostEnd(), NodeClock.system(), DspClient.Config.defaults());
 * ControlRecorder trace = new ControlRecorder(10_000);
 * try (EtherwareNode node = EtherwareNode.builder().nodeId("pendulum").build()) {
 *     node.add(DspProxy.DEFAULT_PROFILE, DspProxy.factory(client));
 *     node.add(PendulumController.DEFAULT_PROFILE,
 *             PendulumController.factory(ControllerConfig.defaults(), GainSet.v1Soft(parameters), trace));
 *     node.start();
 *     board.startRealTime();
 *     // ... a Notifier sends Tick(releaseNs, k, 15 ms) to the controller every 15 ms ...
 *     node.swap(PendulumController.DEFAULT_PROFILE,  // the upgrade of Section VI-C1
 *             PendulumController.factory(ControllerConfig.defaults(), GainSet.v2Tight(parameters), trace));
 * }
 * }</pre>
 *
 * <p>The messages they exchange and the controller's state are records that the code building a node registers on it with
 * {@link io.etherware.pendulum.components.PendulumContents#register(io.etherware.core.message.ContentsTypes)},
 * so they travel as XML
 * between nodes and an upgrade or a migration can carry the controller's state.
 */
package io.etherware.pendulum.components;
