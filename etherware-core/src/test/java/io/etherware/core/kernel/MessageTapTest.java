package io.etherware.core.kernel;

import static org.junit.jupiter.api.Assertions.assertEquals;

import io.etherware.core.message.Message;
import io.etherware.core.message.Profile;
import io.etherware.core.testing.Await;
import io.etherware.core.testing.Num;
import java.util.List;
import java.util.concurrent.CopyOnWriteArrayList;
import org.junit.jupiter.api.Test;

/** A tap sees every message sent, a failing tap loses nothing, a closed tap sees no more. */
class MessageTapTest {

    private static final Profile TARGET = Profile.of("target");

    @Test
    void shouldShowEveryMessageToTheTapAndDeliverItEvenIfATapThrows() throws Exception {
        var handled = new CopyOnWriteArrayList<Long>();
        var seen = new CopyOnWriteArrayList<Long>();
        try (var node = EtherwareNode.builder().nodeId("tapped").build()) {
            node.add(TARGET, () -> (message, context) -> handled.add(message.contentsAs(Num.class).value()));
            node.start();
            MessageTap.Registration failing = node.tap(message -> {
                throw new IllegalStateException("a broken tap");
            });
            MessageTap.Registration watching = node.tap(message -> seen.add(valueOf(message)));
            node.send(TARGET, new Num(1));
            node.send(TARGET, new Num(2));
            Await.until("both handled", () -> handled.size() == 2);
            assertEquals(List.of(1L, 2L), seen, "the tap saw both, in order");

            watching.close();
            failing.close();
            watching.close(); // idempotent
            node.send(TARGET, new Num(3));
            Await.until("the third handled", () -> handled.size() == 3);
            assertEquals(List.of(1L, 2L), seen, "a closed tap sees no more");
            assertEquals(List.of(1L, 2L, 3L), handled);
        }
    }

    private static long valueOf(Message message) {
        return message.contentsAs(Num.class).value();
    }
}
