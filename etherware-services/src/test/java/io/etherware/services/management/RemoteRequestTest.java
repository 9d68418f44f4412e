package io.etherware.services.management;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertInstanceOf;
import static org.junit.jupiter.api.Assertions.assertTrue;

import example.counter.Journal;
import example.counter.SequenceCounter;
import example.counter.SequenceCounterV2;
import io.etherware.core.kernel.EtherwareNode;
import io.etherware.core.message.Message;
import io.etherware.core.message.MessageId;
import io.etherware.core.message.Profile;
import io.etherware.core.message.Text;
import java.util.concurrent.CopyOnWriteArrayList;
import org.junit.jupiter.api.Test;

/**
 * Requests made on another node: refused unless enabled. The other node is simulated by a
 * message whose id carries another node id, as the network messenger would deliver it; the
 * answer goes to its sender, here a local inbox standing in for the remote requester's route.
 */
class RemoteRequestTest {

    private static final Profile COUNTER = UpgradeTest.COUNTER;
    private static final Profile INBOX = Profile.of("inbox");

    private final CopyOnWriteArrayList<Message> inbox = new CopyOnWriteArrayList<>();

    private EtherwareNode node(String nodeId, ManagementConfig config, String journal) {
        var node = EtherwareNode.builder().nodeId(nodeId).build();
        ManagementService.install(node, config);
        node.add(COUNTER, () -> new SequenceCounter(journal));
        node.add(INBOX, () -> (message, context) -> inbox.add(message));
        return node.start();
    }

    private static Message fromElsewhere(EtherwareNode node, long sequence, Object contents) {
        return new Message(Management.profileOf(node.nodeId()), INBOX, node.clock().epochNanos(),
                Management.REQUEST_QOS, (io.etherware.core.message.Contents) contents,
                new MessageId("elsewhere", sequence), null);
    }

    @Test
    void shouldRefuseAnUpgradeMadeOnAnotherNodeWhenRemoteRequestsAreNotEnabled() {
        Journal.create("remote-refused");
        try (var node = node("managed", ManagementConfig.defaults(), "remote-refused")) {
            node.send(fromElsewhere(node, 41, new UpgradeRequest(COUNTER, SequenceCounterV2.class.getName(), null,
                    "remote-refused")));
            Await.until("the answer", () -> inbox.size() == 1);

            Message answer = inbox.getFirst();
            assertEquals(new MessageId("elsewhere", 41), answer.correlationId(), "an answer to the request");
            var failure = assertInstanceOf(ManagementFailure.class, answer.contents());
            assertEquals(ManagementFailure.Reason.REMOTE_REFUSED, failure.reason());
            assertTrue(failure.error().contains("made on node 'elsewhere'"), failure.error());
            assertTrue(failure.error().contains("acceptRemoteRequests(true)"), failure.error());
            assertEquals(SequenceCounter.class, node.shell(COUNTER).logicType(), "nothing was upgraded");
        }
    }

    @Test
    void shouldServeAnUpgradeMadeOnAnotherNodeWhenRemoteRequestsAreEnabled() {
        Journal.create("remote-accepted");
        try (var node = node("managed-open", ManagementConfig.builder().acceptRemoteRequests(true).build(),
                "remote-accepted")) {
            node.send(fromElsewhere(node, 7, new UpgradeRequest(COUNTER, SequenceCounterV2.class.getName(), null,
                    "remote-accepted")));
            Await.until("the answer", () -> inbox.size() == 1);
            var result = assertInstanceOf(UpgradeResult.class, inbox.getFirst().contents());
            assertEquals(SequenceCounterV2.class.getName(), result.newImplementation());
            assertEquals(SequenceCounterV2.class, node.shell(COUNTER).logicType());
        }
    }

    @Test
    void shouldCountRefusalsAndAnswerARequestOfAKindItDoesNotServe() {
        Journal.create("remote-counted");
        var node = EtherwareNode.builder().nodeId("managed-counted").build();
        ManagementService service = ManagementService.install(node, ManagementConfig.defaults());
        node.add(COUNTER, () -> new SequenceCounter("remote-counted"));
        node.add(INBOX, () -> (message, context) -> inbox.add(message));
        try (node) {
            node.start();
            node.send(fromElsewhere(node, 1, new UpgradeRequest(COUNTER, SequenceCounterV2.class.getName(), null,
                    "remote-counted")));
            node.send(new Message(Management.profileOf(node.nodeId()), INBOX, node.clock().epochNanos(),
                    Management.REQUEST_QOS, new Text("reboot"), node.newMessageId(), null));
            Await.until("two answers", () -> inbox.size() == 2);
            var unknownKind = inbox.stream().map(Message::contents).map(ManagementFailure.class::cast)
                    .filter(failure -> failure.reason() == ManagementFailure.Reason.BAD_REQUEST).findFirst()
                    .orElseThrow();
            assertTrue(unknownKind.error().contains("does not serve Text messages"), unknownKind.error());
            assertEquals(2, service.refusedCount());
            assertEquals(0, service.upgradedCount());
        }
    }
}
