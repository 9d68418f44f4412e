package io.etherware.services.notifier;

import static org.junit.jupiter.api.Assertions.assertEquals;

import io.etherware.core.component.Component;
import io.etherware.core.component.ComponentContext;
import io.etherware.core.kernel.EtherwareNode;
import io.etherware.core.message.Criticality;
import io.etherware.core.message.Message;
import io.etherware.core.message.Profile;
import io.etherware.core.message.Tick;
import io.etherware.testkit.Await;
import java.util.List;
import java.util.concurrent.LinkedBlockingQueue;
import org.junit.jupiter.api.Test;

/**
 * The README's Notifier example, verbatim between the markers, so that
 * it always compiles and runs. Keep the README in step with this body. The Notifier thread asks
 * for SCHED_FIFO 82 here, as by default; it only sleeps (no spin).
 */
class NotifierReadmeExampleTest {

    @Test
    void shouldActivateTheControllerEvery15MsWithHighTicks() {
        List<Tick> received;
        try (var node = EtherwareNode.builder().nodeId("pendulum").build()) {
            // README example begins
            var ticks = new LinkedBlockingQueue<Tick>();
            var notifier = Notifier.install(node, NotifierConfig.defaults()); // thread asks for SCHED_FIFO 82; warns once if refused
            node.add(Profile.of("controller"), () -> new Component() {
                @Override public void onStart(ComponentContext context) {
                    context.request(notifier.profile(), TickSubscribe.periodic(Criticality.HIGH, 15_000_000L))
                            .whenComplete((reply, failure) -> { // the Notifier answers: accepted, or refused with the reason
                                if (failure != null || !reply.contentsAs(NotifierReply.class).accepted()) {
                                    context.logger().error("no Ticks: {}", failure != null ? failure : reply.contents());
                                }
                            });
                }
                @Override public void onMessage(Message message, ComponentContext context) {
                    if (message.contents() instanceof Tick tick) ticks.add(tick); // tick.releaseNs(): when it was due
                }
            });
            // README example ends
            node.start();
            Await.until(() -> ticks.size() + " Ticks", 20_000, () -> ticks.size() >= 4);
            received = List.copyOf(ticks);
        }
        Tick first = received.getFirst();
        for (Tick tick : received) {
            assertEquals(15_000_000L, tick.periodNs());
            assertEquals(first.releaseNs() + (tick.sequence() - first.sequence()) * 15_000_000L, tick.releaseNs());
        }
    }
}
