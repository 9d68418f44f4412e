package io.etherware.services.network;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.etherware.testkit.Await;
import java.time.Duration;
import java.util.Optional;
import org.junit.jupiter.api.AfterEach;
import org.junit.jupiter.api.BeforeEach;
import org.junit.jupiter.api.Test;

/**
 * {@link NetworkMessenger#goneWithoutGoodbye}: how a node sees a peer's process end. A raw peer
 * ({@link RawPeer}) connects on lane 0 and leaves in each of the ways a peer can: its socket closed
 * with no BYE (as when its process ends), after a BYE, and coming back as the same process or as a
 * restarted one (a new incarnation).
 */
class NetworkGoodbyeIT {

    private static final String GHOST = "ghost";
    private TestNode target;

    @BeforeEach
    void start() {
        target = TestNode.start("target", TestNode.config());
    }

    @AfterEach
    void stop() {
        target.close();
    }

    /** Connects as process {@code incarnation} of the ghost; returns once the node made it its lane's connection. */
    private RawPeer connect(long incarnation) throws Exception {
        var peer = new RawPeer(target.address());
        peer.incarnation = incarnation;
        peer.handshake(GHOST);
        while (peer.read().type() != RawPeer.ANNOUNCE) {
            // the node announces its profiles on a connection it took
        }
        return peer;
    }

    @Test
    void shouldSeeAPeerGoneWithoutAGoodbyeOnlyUntilTheSameProcessComesBack() throws Exception {
        assertEquals(Optional.empty(), target.net.goneWithoutGoodbye(GHOST), "unknown: not gone");
        RawPeer first = connect(1);
        assertEquals(Optional.empty(), target.net.goneWithoutGoodbye(GHOST), "connected");
        first.close(); // no BYE: as when its process ends
        Await.until("seen gone", () -> target.net.goneWithoutGoodbye(GHOST).isPresent());
        Duration early = target.net.goneWithoutGoodbye(GHOST).orElseThrow();
        Thread.sleep(50);
        assertTrue(target.net.goneWithoutGoodbye(GHOST).orElseThrow().compareTo(early) > 0, "counts since it left");

        try (RawPeer again = connect(1)) { // the same process: it had only lost its connection
            assertEquals(Optional.empty(), target.net.goneWithoutGoodbye(GHOST));
        }
    }

    @Test
    void shouldNotTakeAPeerThatSaidGoodbyeForGone() throws Exception {
        try (RawPeer peer = connect(1)) {
            peer.bye(CloseReason.SHUTDOWN.code(), "closing its messenger");
            peer.readUntilClosed();
        }
        Await.until("disconnected", () -> target.net.peer(GHOST).map(status -> !status.connected()).orElse(true));
        Thread.sleep(100);
        assertEquals(Optional.empty(), target.net.goneWithoutGoodbye(GHOST), "it said goodbye");
    }

    @Test
    void shouldKeepAProcessThatLeftGoneWhenItsNodeRestarts() throws Exception {
        connect(1).close(); // the process ends
        Await.until("seen gone", () -> target.net.goneWithoutGoodbye(GHOST).isPresent());
        try (RawPeer restarted = connect(2)) { // the node's next process
            assertTrue(target.net.goneWithoutGoodbye(GHOST).isPresent(), "the first process is still gone");
        }
    }
}
