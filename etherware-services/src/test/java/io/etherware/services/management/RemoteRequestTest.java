package io.etherware.services.management;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertInstanceOf;
import static org.junit.jupiter.api.Assertions.assertTrue;

import example.counter.Journal;
import example.counter.SequenceCounter;
import example.counter.SequenceCounterV2;
import io.etherware.core.kernel.EtherwareNode;
import io.etherware.core.message.Contents;
import io.etherware.core.message.Message;
import io.etherware.core.message.MessageId;
import io.etherware.core.message.Origin;
import io.etherware.core.message.Profile;
import io.etherware.core.message.Text;
import io.etherware.services.management.AccessRule.Operation;
import io.etherware.testkit.Await;
import java.time.Duration;
import java.util.Set;
import java.util.concurrent.CopyOnWriteArrayList;
import org.junit.jupiter.api.Test;

/**
 * Upgrade requests that arrived from other nodes: decided by their {@link Origin}, as the network
 * layer sets it from the connection, against the access list; never by the message id. The
 * remote request is simulated as the network layer delivers it ({@code withOrigin}); its answer
 * goes to its sender, here a local inbox standing in for the remote requester's route.
 */
class RemoteRequestTest {

    private static final Profile COUNTER = Profile.parse("counter[loop=1]");
    private static final Profile INBOX = Profile.of("inbox");
    private static final String CONTROLLER = "controller-node";

    private final CopyOnWriteArrayList<Message> inbox = new CopyOnWriteArrayList<>();
    private ManagementService service;

    private EtherwareNode node(String nodeId, ManagementConfig config, String journal) {
        Journal.create(journal);
        var node = EtherwareNode.builder().nodeId(nodeId).build();
        service = ManagementService.install(node, config);
        node.add(COUNTER, () -> new SequenceCounter(journal));
        node.add(INBOX, () -> (message, context) -> inbox.add(message));
        return node.start();
    }

    /** Lets {@value #CONTROLLER} upgrade the counter. */
    private static ManagementConfig controllerMayUpgrade() {
        return answerAtOnce().allowRemote(CONTROLLER, Set.of(Operation.UPGRADE), "counter").build();
    }

    /**
     * The default access list, and an upgrade's answer that does not wait (1 s by default) for the
     * new logic's first message, which these tests never send: they check who is served, not the gap.
     */
    private static ManagementConfig.Builder answerAtOnce() {
        return ManagementConfig.builder().firstMessageWait(Duration.ZERO);
    }

    /** An upgrade of the counter to V2 whose id says {@code idNode} made it, arrived through {@code origin}. */
    private static Message upgrade(EtherwareNode node, String idNode, long sequence, Origin origin, String journal) {
        Contents request = new UpgradeRequest(COUNTER, SequenceCounterV2.class.getName(), null, journal);
        return new Message(Management.profileOf(node.nodeId()), INBOX, node.clock().epochNanos(),
                Management.REQUEST_QOS, request, new MessageId(idNode, sequence), null).withOrigin(origin);
    }

    private ManagementFailure refusal(int answers) {
        Await.until(answers + " answer(s)", () -> inbox.size() == answers);
        Message answer = inbox.get(answers - 1);
        var failure = assertInstanceOf(ManagementFailure.class, answer.contents(), "refused, not served");
        assertEquals(ManagementFailure.Reason.REMOTE_REFUSED, failure.reason(), failure.error());
        assertEquals("upgrade", failure.operation());
        assertEquals(COUNTER, failure.target());
        return failure;
    }

    private static void assertNotUpgraded(EtherwareNode node) {
        assertEquals(SequenceCounter.class, node.shell(COUNTER).logicType(), "nothing was upgraded");
    }

    @Test
    void shouldRefuseAnUpgradeFromANodeTheAccessListDoesNotNameAndSayHowToAllowIt() {
        try (var node = node("managed", controllerMayUpgrade(), "remote-stranger")) {
            node.send(upgrade(node, "stranger", 41, Origin.direct("stranger", true), "remote-stranger"));

            ManagementFailure failure = refusal(1);
            assertEquals(new MessageId("stranger", 41), inbox.getFirst().correlationId(), "an answer to the request");
            assertTrue(failure.error().contains("node 'stranger' may not upgrade 'counter[loop=1]' on node 'managed'"),
                    failure.error());
            assertTrue(failure.error().contains("allowRemote(\"stranger\", Set.of(Operation.UPGRADE), \"counter[loop=1]\")"),
                    failure.error());
            assertNotUpgraded(node);
            assertEquals(1, service.refusedCount());
        }
    }

    @Test
    void shouldRefuseAllRemoteManagementWithTheDefaultConfiguration() {
        try (var node = node("managed-default", ManagementConfig.defaults(), "remote-default")) {
            node.send(upgrade(node, CONTROLLER, 1, Origin.direct(CONTROLLER, true), "remote-default"));
            ManagementFailure failure = refusal(1);
            assertTrue(failure.error().contains("the access list is empty"), failure.error());
            assertNotUpgraded(node);
        }
    }

    @Test
    void shouldServeAnUpgradeFromANodeTheAccessListAllows() {
        try (var node = node("managed-open", controllerMayUpgrade(), "remote-allowed")) {
            node.send(upgrade(node, CONTROLLER, 7, Origin.direct(CONTROLLER, true), "remote-allowed"));
            Await.until("the answer", () -> inbox.size() == 1);
            var result = assertInstanceOf(UpgradeResult.class, inbox.getFirst().contents(), () -> inbox.toString());
            assertEquals(SequenceCounterV2.class.getName(), result.newImplementation());
            assertEquals(SequenceCounterV2.class, node.shell(COUNTER).logicType());
            assertEquals(0, service.refusedCount());
        }
    }

    @Test
    void shouldRefuseARequestWhoseIdNamesAnotherNodeThanTheOneItCameFrom() {
        // The attack: the id's node part is text the peer wrote. Naming the managed node itself
        // made the old check take the request for a local one; naming an allowed node must not help.
        try (var node = node("managed-forged", controllerMayUpgrade(), "remote-forged")) {
            node.send(upgrade(node, "managed-forged", 5, Origin.direct("stranger", true), "remote-forged"));
            ManagementFailure asLocal = refusal(1);
            assertTrue(asLocal.error().contains("node 'stranger' may not upgrade"), asLocal.error());

            node.send(upgrade(node, CONTROLLER, 6, Origin.direct("stranger", true), "remote-forged"));
            ManagementFailure asAllowed = refusal(2);
            assertTrue(asAllowed.error().contains("node 'stranger' may not upgrade"), asAllowed.error());
            assertNotUpgraded(node);
            assertEquals(2, service.refusedCount());
        }
    }

    @Test
    void shouldRefuseARelayedRequestEvenFromAnAllowedNode() {
        try (var node = node("managed-relayed", controllerMayUpgrade(), "remote-relayed")) {
            node.send(upgrade(node, CONTROLLER, 3, new Origin(CONTROLLER, "relay-node", 1, true), "remote-relayed"));
            ManagementFailure failure = refusal(1);
            assertTrue(failure.error().contains("relayed to node 'managed-relayed' by node 'relay-node'"),
                    failure.error());
            assertTrue(failure.error().contains("a relay must not lend its rights"), failure.error());
            assertNotUpgraded(node);
        }
    }

    @Test
    void shouldServeARequestMadeOnTheNodeItselfWithAnEmptyAccessList() {
        try (var node = node("managed-local", answerAtOnce().build(), "remote-local")) {
            node.send(upgrade(node, node.nodeId(), 9, null, "remote-local"));
            Await.until("the answer", () -> inbox.size() == 1);
            assertInstanceOf(UpgradeResult.class, inbox.getFirst().contents(), () -> inbox.toString());
            assertEquals(SequenceCounterV2.class, node.shell(COUNTER).logicType());
        }
    }

    @Test
    void shouldRefuseAnOperationOrAComponentNoRuleCovers() {
        ManagementConfig config = ManagementConfig.builder()
                .allowRemote(CONTROLLER, Set.of(Operation.MIGRATE), "counter")
                .allowRemote(CONTROLLER, Set.of(Operation.UPGRADE), "counter[loop=2]")
                .allowRemote("*", Set.of(Operation.UPGRADE), "count").build();
        try (var node = node("managed-narrow", config, "remote-narrow")) {
            node.send(upgrade(node, CONTROLLER, 1, Origin.direct(CONTROLLER, true), "remote-narrow"));
            ManagementFailure failure = refusal(1);
            assertTrue(failure.error().contains("no rule of the access list"), failure.error());
            assertNotUpgraded(node);
        }
    }

    @Test
    void shouldRefuseARequestOverAnUnauthenticatedLinkUnlessThatWasChosen() {
        try (var node = node("managed-plain", controllerMayUpgrade(), "remote-plain")) {
            node.send(upgrade(node, CONTROLLER, 1, Origin.direct(CONTROLLER, false), "remote-plain"));
            ManagementFailure failure = refusal(1);
            assertTrue(failure.error().contains("did not authenticate it"), failure.error());
            assertTrue(failure.error().contains("allowUnauthenticatedLinks(true)"), failure.error());
            assertNotUpgraded(node);
        }
        inbox.clear();
        ManagementConfig loopback = answerAtOnce().allowUnauthenticatedLinks(true)
                .allowRemote(CONTROLLER, Set.of(Operation.UPGRADE), "counter").build();
        try (var node = node("managed-loopback", loopback, "remote-loopback")) {
            node.send(upgrade(node, CONTROLLER, 2, Origin.direct(CONTROLLER, false), "remote-loopback"));
            Await.until("the answer", () -> inbox.size() == 1);
            assertInstanceOf(UpgradeResult.class, inbox.getFirst().contents(), () -> inbox.toString());
        }
    }

    @Test
    void shouldCountRefusalsAndAnswerARequestOfAKindItDoesNotServe() {
        try (var node = node("managed-counted", ManagementConfig.defaults(), "remote-counted")) {
            node.send(upgrade(node, "elsewhere", 1, Origin.direct("elsewhere", true), "remote-counted"));
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
