package io.etherware.services.status;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.etherware.core.codec.MessageCodec;
import io.etherware.core.kernel.EtherwareNode;
import io.etherware.core.message.Contents;
import io.etherware.core.message.ContentsTypes;
import io.etherware.core.message.Message;
import io.etherware.core.message.MessageId;
import io.etherware.core.message.Profile;
import io.etherware.core.message.Text;
import io.etherware.testkit.Await;
import java.time.Duration;
import java.util.List;
import java.util.concurrent.TimeUnit;
import org.junit.jupiter.api.Test;

/** A node's status: exact through the codec, and answered by its status service. */
class StatusTest {

    private static Message carrying(Contents contents) {
        return new Message(Status.profileOf("plant-1"), Profile.parse("etherware.node[id=console]"), 1_000L,
                Status.REQUEST_QOS, contents, new MessageId("console", 7), null);
    }

    @Test
    void shouldRoundTripTheRequestAndTheStatusThroughTheCodec() {
        var types = new ContentsTypes();
        Status.registerContents(types);
        var codec = new MessageCodec(types);
        var status = new NodeStatus("plant-1", 123_456_789L, "realtime [0:SCHED_OTHER, 1:SCHED_FIFO/80]",
                List.of(new NodeStatus.ComponentEntry("controller[pendulum=1]", "RUNNING", "a.B", 10, 1, 0, 2, 900)),
                List.of(new NodeStatus.DispatcherEntry(1, 100, 2, 0, 12_000, 40_000, 90_000)),
                List.of(new NodeStatus.PeerEntry("node2", true, "127.0.0.1:7401", 0, 3, -1_500L, 60_000L),
                        new NodeStatus.PeerEntry("node3", false, "", 4, 0, null, null)),
                new NodeStatus.Counters(10, 1, 0, 2, 0, 2));
        for (Contents contents : List.of(new StatusRequest(), status)) {
            Message message = carrying(contents);
            assertEquals(message, codec.decode(codec.encode(message)), contents.getClass().getSimpleName());
        }
    }

    @Test
    void shouldAnswerWithTheComponentsAndTheirCounters() throws Exception {
        try (EtherwareNode node = EtherwareNode.builder().nodeId("status-node").build().start()) {
            var echo = Profile.of("echo");
            node.add(echo, () -> (message, context) -> { });
            StatusService.install(node, null);
            for (int i = 0; i < 3; i++) {
                node.send(echo, new Text("hello " + i));
            }
            Await.until("the echo component handled 3", () -> node.shell(echo).handledCount() == 3);

            NodeStatus status = Status.request(node, "status-node", Duration.ofSeconds(10)).get(10, TimeUnit.SECONDS);

            assertEquals("status-node", status.nodeId());
            var entry = status.components().stream().filter(c -> c.profile().equals("echo")).findFirst().orElseThrow();
            assertEquals("RUNNING", entry.state());
            assertEquals(3, entry.handled());
            assertTrue(status.components().stream().anyMatch(c -> c.profile().equals(Status.profileOf("status-node")
                    .toString())), status::toString);
            assertTrue(status.peers().isEmpty());
            assertTrue(status.counters().handled() >= 3, status::toString);
        }
    }
}
