package io.etherware.rt;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.etherware.core.kernel.EtherwareNode;
import io.etherware.core.message.Criticality;
import io.etherware.core.message.Profile;
import io.etherware.core.message.QoS;
import io.etherware.core.message.Text;
import io.etherware.rt.scheduling.RealtimeScheduler;
import java.time.Duration;
import org.junit.jupiter.api.Test;

/**
 * The README's "Configuring a node with the real-time scheduler" example, verbatim between the
 * markers, so that it always compiles and runs. Keep the README in step with this body.
 */
class ReadmeSchedulerExampleTest {

    @Test
    void shouldRunTheReadmeSchedulerExample() {
        // README example begins
        var scheduler = RealtimeScheduler.withDefaults(); // Table II dispatchers, Algorithm 1 placement
        Profile controller = Profile.of("controller");
        QoS control = QoS.periodic(Criticality.HIGH, Duration.ofMillis(15).toNanos()); // dispatcher 1
        try (var node = EtherwareNode.builder().nodeId("plant-1").scheduler(() -> scheduler).build()) {
            node.add(controller, () -> (message, context) -> context.logger().info("got {}", message.contents()));
            node.start(); // logs one line per dispatcher: OS priority requested vs granted
            node.send(controller, new Text("sample"), control);
        }
        long p99Ns = scheduler.stats().dispatcher(1).startLatencyNs().percentileNs(99); // release to start
        // README example ends

        assertEquals(1, scheduler.stats().dispatcher(1).jobsRun(), "the HIGH message ran on dispatcher 1");
        assertEquals(1, scheduler.stats().jobsRun());
        assertTrue(p99Ns > 0, "start latency recorded");
        assertEquals(4, scheduler.platformReport().threads().size());
    }
}
