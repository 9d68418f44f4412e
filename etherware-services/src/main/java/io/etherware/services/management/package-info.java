/**
 * Runtime management of a node's components (paper Sections III-B and VI-C): today, upgrading a
 * component's logic while it runs, with nothing lost.
 *
 * <h2>Using it</h2>
 * <pre>{@code
 * ManagementService.install(node, ManagementConfig.builder().allowDirectory(Path.of("/opt/plant/upgrades")).build());
 * ...
 * UpgradeResult result = Management.upgrade(node, "plant-1", Profile.parse("controller[car=1]"),
 *         Implementation.fromJar(Path.of("/opt/plant/upgrades/controller-2.jar"), "com.example.ControllerV2")
 *                 .withConfiguration("k1=-12.1,k2=95.3")).join();
 * }</pre>
 * The new class's contract is on {@link io.etherware.services.management.Implementation}; the
 * service's steps and threads on {@link io.etherware.services.management.ManagementService}.
 *
 * <h2>The protocol</h2>
 * Management requests are ordinary messages to {@code etherware.management[node=<id>]}, sent at
 * {@link io.etherware.core.message.Criticality#HIGH HIGH} criticality, with registered contents so
 * they can cross nodes:
 * <table>
 *   <caption>Contents types</caption>
 *   <tr><th>name</th><th>record</th><th>meaning</th></tr>
 *   <tr><td>{@code etherware.upgrade}</td><td>{@link io.etherware.services.management.UpgradeRequest}</td>
 *       <td>request: replace a component's logic</td></tr>
 *   <tr><td>{@code etherware.upgradeResult}</td><td>{@link io.etherware.services.management.UpgradeResult}</td>
 *       <td>answer: what replaced what, load / pause / gap / total in ns</td></tr>
 *   <tr><td>{@code etherware.managementFailure}</td>
 *       <td>{@link io.etherware.services.management.ManagementFailure}</td>
 *       <td>answer: refused or failed, with a reason and a message; the old logic serves on</td></tr>
 * </table>
 * Migration will add its own request and answer types to the same service.
 *
 * <h2>Guards</h2>
 * Code comes only from the node's class path or from jars whose canonical path (symbolic links
 * resolved) lies inside an allowlisted directory. A request whose message id was made on another
 * node is refused unless {@link io.etherware.services.management.ManagementConfig#acceptRemoteRequests()};
 * links are not authenticated yet, so enable it only on a trusted network.
 *
 * <p>Thread-safety of each type is stated on the type.
 */
package io.etherware.services.management;
