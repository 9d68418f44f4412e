package io.etherware.services.management;

import java.net.InetSocketAddress;
import java.time.Duration;

/**
 * The other JVM of {@link MigrationAcrossJvmsIT}: a node that dials the test's node and can
 * receive (and send back) migrated components. Prints {@code READY} once connected and runs
 * until its standard input closes.
 *
 * <p>Arguments: node id, host and port to dial, the migration step timeout in ms; optionally the
 * id of the test's node and the first-message wait in ms.
 */
public final class MigrationPeer {

    private MigrationPeer() {
    }

    public static void main(String[] args) throws Exception {
        String nodeId = args[0];
        var parent = new InetSocketAddress(args[1], Integer.parseInt(args[2]));
        Duration stepTimeout = Duration.ofMillis(Long.parseLong(args[3]));
        ManagementConfig.Builder config = MigrationNode.config().migrationStepTimeout(stepTimeout)
                .handoverWait(stepTimeout.multipliedBy(2));
        if (args.length > 5) {
            config.firstMessageWait(Duration.ofMillis(Long.parseLong(args[5])));
        }
        try (var node = MigrationNode.start(nodeId, config.build(), parent)) {
            node.awaitManagementOf(args.length > 4 ? args[4] : "jvm-a");
            System.out.println("READY");
            System.out.flush();
            while (System.in.read() >= 0) {
                // runs until the test closes our input (or kills us)
            }
        }
    }
}
