package io.etherware.services.network;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertNotEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.etherware.core.kernel.Endpoint;
import io.etherware.core.message.Profile;
import io.etherware.core.message.Text;
import io.etherware.testkit.Await;
import java.time.Duration;
import java.util.Set;
import java.util.concurrent.CountDownLatch;
import org.junit.jupiter.api.Test;

/** Who is connected to whom, and which node a profile routes to. */
class NetworkTopologyIT {

    private static final Profile DUP = Profile.of("dup");

    @Test
    void shouldKeepOneConnectionDialedByTheLowerIdWhenBothNodesDialAtOnce() throws Exception {
        for (int round = 0; round < 5; round++) {
            try (var a = TestNode.start("a", TestNode.config());
                 var b = TestNode.start("b", TestNode.config())) {
                var go = new CountDownLatch(1);
                Thread dialB = Thread.ofPlatform().start(() -> {
                    awaitQuietly(go);
                    b.net.addPeer(a.address());
                });
                Thread dialA = Thread.ofPlatform().start(() -> {
                    awaitQuietly(go);
                    a.net.addPeer(b.address());
                });
                go.countDown();
                dialA.join();
                dialB.join();
                assertTrue(a.net.awaitConnected("b", Duration.ofSeconds(30)));
                assertTrue(b.net.awaitConnected("a", Duration.ofSeconds(30)));
                Thread.sleep(300); // any duplicate has been settled by now, and none may come back
                long openedA = a.net.stats().connectionsOpened();
                long openedB = b.net.stats().connectionsOpened();
                Thread.sleep(300);
                assertEquals(openedA, a.net.stats().connectionsOpened(), "round " + round + ": no flapping");
                assertEquals(openedB, b.net.stats().connectionsOpened(), "round " + round + ": no flapping");
                assertEquals(1, a.net.stats().connectedPeers());
                assertEquals(1, b.net.stats().connectedPeers());
                // The survivor is a's dial: on a it goes to b's listening port, on b it comes from elsewhere.
                String onA = a.net.peer("b").orElseThrow().remote().orElseThrow();
                String onB = b.net.peer("a").orElseThrow().remote().orElseThrow();
                assertTrue(onA.endsWith(":" + b.address().getPort()), "round " + round + ": " + onA);
                assertNotEquals(":" + a.address().getPort(), onB.substring(onB.lastIndexOf(':')), "round " + round);
                b.node.add(Profile.of("echo"), () -> (message, context) -> context.reply(message, message.contents()));
                assertTrue(a.net.awaitResolvable(Profile.of("echo"), Duration.ofSeconds(30)));
                assertEquals(new Text("r" + round), a.node.requestBlocking(Profile.of("echo"), new Text("r" + round))
                        .contents());
            }
        }
    }

    @Test
    void shouldAnnounceProfilesAddedAndRemovedAfterConnecting() throws Exception {
        try (var b = TestNode.start("b", TestNode.config());
             var a = TestNode.start("a", TestNode.config().peer(b.address()))) {
            assertTrue(a.net.awaitResolvable(b.node.profile(), Duration.ofSeconds(30)), "the node profile is routed");
            Profile late = Profile.of("late", "node", "b");
            b.node.add(late, () -> (message, context) -> context.reply(message, new Text("late")));
            assertTrue(a.net.awaitResolvable(late, Duration.ofSeconds(30)));
            assertEquals(Set.of(b.node.profile(), late), a.net.peer("b").orElseThrow().profiles());
            b.node.remove(late);
            Await.until("a unroutes the removed profile", () -> !a.node.registry().profiles().contains(late));
        }
    }

    @Test
    void shouldKeepAProfileAnnouncedTwiceRoutedToTheFirstClaimantAndFollowTheSecondWhenItLeaves() throws Exception {
        try (var b = TestNode.start("b", TestNode.config());
             var c = TestNode.start("c", TestNode.config());
             var a = TestNode.start("a", TestNode.config().peer(c.address()).peer(b.address()))) {
            c.node.add(DUP, () -> (message, context) -> context.reply(message, new Text("from c")));
            assertTrue(a.net.awaitResolvable(DUP, Duration.ofSeconds(30)));
            Await.until("a routes dup to c", () -> routesTo(a, "c", DUP));
            assertTrue(a.net.awaitConnected("b", Duration.ofSeconds(30)));
            // b, whose id sorts lower, announces it too: the first claimant keeps it.
            b.node.add(DUP, () -> (message, context) -> context.reply(message, new Text("from b")));
            // Announcements are whole sets, in order: once a routes the marker, it has b's claim.
            Profile marker = Profile.of("marker", "node", "b");
            b.node.add(marker, () -> (message, context) -> { });
            Await.until("a has b's announcement", () -> routesTo(a, "b", marker));
            assertEquals(new Text("from c"), a.node.requestBlocking(DUP, new Text("?")).contents());
            assertTrue(routesTo(a, "c", DUP), "the later claim does not draw the route");

            c.node.remove(DUP);
            Await.until("a routes dup to b", () -> routesTo(a, "b", DUP));
            assertEquals(new Text("from b"), a.node.requestBlocking(DUP, new Text("?")).contents());
        }
    }

    @Test
    void shouldLetALocalComponentWinOverAnAnnouncedProfileAndRestoreTheRouteWhenItLeaves() throws Exception {
        try (var b = TestNode.start("b", TestNode.config());
             var a = TestNode.start("a", TestNode.config().peer(b.address()))) {
            b.node.add(DUP, () -> (message, context) -> context.reply(message, new Text("from b")));
            assertTrue(a.net.awaitResolvable(DUP, Duration.ofSeconds(30)));
            a.node.add(DUP, () -> (message, context) -> context.reply(message, new Text("from a")));
            assertTrue(a.node.registry().resolve(DUP) instanceof Endpoint.Local);
            assertEquals(new Text("from a"), a.node.requestBlocking(DUP, new Text("?")).contents());
            // b does not route to a's dup either: its own comes first.
            assertEquals(new Text("from b"), b.node.requestBlocking(DUP, new Text("?")).contents());

            a.node.remove(DUP);
            Await.until("a routes dup to b again", () -> a.node.registry().profiles().contains(DUP)
                    && a.node.registry().resolve(DUP) instanceof Endpoint.Remote);
            assertEquals(new Text("from b"), a.node.requestBlocking(DUP, new Text("?")).contents());
        }
    }

    private static boolean routesTo(TestNode from, String nodeId, Profile profile) {
        return from.net.peer(nodeId).map(peer -> peer.profiles().contains(profile)).orElse(false);
    }

    private static void awaitQuietly(CountDownLatch latch) {
        try {
            latch.await();
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
        }
    }
}
