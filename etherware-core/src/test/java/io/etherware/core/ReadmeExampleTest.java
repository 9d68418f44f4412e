package io.etherware.core;

import static org.junit.jupiter.api.Assertions.assertEquals;

import io.etherware.core.component.Component;
import io.etherware.core.component.ComponentContext;
import io.etherware.core.kernel.EtherwareNode;
import io.etherware.core.message.Contents;
import io.etherware.core.message.Message;
import io.etherware.core.message.Profile;
import java.util.concurrent.LinkedBlockingQueue;
import java.util.concurrent.TimeUnit;
import org.junit.jupiter.api.Test;

/**
 * The README's two-component example, verbatim between the markers, so that it always compiles
 * and runs. Keep the README in step with this body.
 */
class ReadmeExampleTest {

    @Test
    void shouldRunTheReadmeExample() throws Exception {
        // README example begins
        record Reading(double celsius) implements Contents {}
        record Command(double heaterPower) implements Contents {}
        var applied = new LinkedBlockingQueue<Command>();

        try (var node = EtherwareNode.builder().nodeId("demo").build()) {
            // The controller answers each reading with a heater command.
            node.add(Profile.of("controller", "room", "1"), () -> (message, context) -> {
                double errorCelsius = 21.0 - message.contentsAs(Reading.class).celsius();
                context.reply(message, new Command(Math.clamp(0.5 * errorCelsius, 0.0, 1.0)));
            });
            // The plant reports a reading when it starts and applies the commands it gets.
            node.add(Profile.of("plant", "room", "1"), () -> new Component() {
                @Override
                public void onStart(ComponentContext context) {
                    context.send(Profile.of("controller"), new Reading(19.0)); // a query: role only
                }

                @Override
                public void onMessage(Message message, ComponentContext context) {
                    applied.add(message.contentsAs(Command.class));
                }
            });
            node.start();
            Command first = applied.poll(5, TimeUnit.SECONDS); // Command[heaterPower=1.0]
            assertEquals(new Command(1.0), first);
        }
        // README example ends
    }
}
