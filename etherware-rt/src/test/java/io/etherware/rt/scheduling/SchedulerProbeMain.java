package io.etherware.rt.scheduling;

import io.etherware.core.kernel.EtherwareNode;
import io.etherware.core.message.Criticality;
import io.etherware.core.message.Empty;
import io.etherware.core.message.Profile;
import io.etherware.core.message.QoS;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.TimeoutException;

/**
 * A child JVM for {@link PlatformRefusalChildJvmIT}: starts a node with the default real-time
 * scheduler (optionally locking memory), sends one HIGH message, prints which thread handled it,
 * the platform report and the locked memory, and exits. Output lines are prefixed so the parent
 * can pick them out; the node's own log goes to stderr.
 */
public final class SchedulerProbeMain {

    private SchedulerProbeMain() {
    }

    public static void main(String[] args) throws Exception {
        boolean lockMemory = args.length > 0 && args[0].equals("lock");
        var scheduler = new RealtimeScheduler(RealtimeSchedulerConfig.builder().lockMemory(lockMemory).build());
        var ranOn = new CompletableFuture<String>();
        Profile probe = Profile.of("probe");
        try (var node = EtherwareNode.builder().nodeId("probe").scheduler(() -> scheduler).build()) {
            node.add(probe, () -> (message, context) -> ranOn.complete(Thread.currentThread().getName()));
            node.start();
            node.send(probe, Empty.INSTANCE, QoS.of(Criticality.HIGH));
            try {
                System.out.println("RAN HIGH on " + ranOn.get(10, TimeUnit.SECONDS));
            } catch (TimeoutException e) {
                System.out.println("HIGH NOT RUN");
            }
            scheduler.platformReport().lines().forEach(line -> System.out.println("REPORT " + line));
            for (String line : Files.readAllLines(Path.of("/proc/self/status"))) {
                if (line.startsWith("VmLck:")) {
                    System.out.println("VMLCK " + line.substring(6).strip());
                }
            }
        }
    }
}
