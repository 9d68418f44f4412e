package io.etherware.services.network;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.etherware.core.kernel.EtherwareNode;
import io.etherware.core.message.Contents;
import io.etherware.core.message.ContentsTypes;
import io.etherware.core.message.Message;
import io.etherware.core.message.Profile;
import io.etherware.core.message.Text;
import java.time.Duration;
import org.junit.jupiter.api.Test;

/**
 * The README's two-node example (notes/readme-network.md), verbatim between the markers, so that
 * it always compiles and runs. Keep the README in step with this body.
 */
class ReadmeExampleIT {

    @Test
    void shouldRunTheTwoNodeReadmeExample() throws Exception {
        // README example begins
        record Reading(double celsius) implements Contents {}
        var types = new ContentsTypes().register("reading", Reading.class); // on every node: the wire name
        try (var plant = EtherwareNode.builder().nodeId("plant").contentsTypes(types).build().start();
             var plantNet = NetworkMessenger.start(plant, NetworkConfig.builder().listen("127.0.0.1", 0).build());
             var control = EtherwareNode.builder().nodeId("control").contentsTypes(types).build().start();
             var controlNet = NetworkMessenger.start(control, NetworkConfig.builder().peer(plantNet.localAddress()).build())) {
            plant.add(Profile.of("thermometer"), () -> (message, context) -> context.reply(message, new Reading(19.5)));
            controlNet.awaitResolvable(Profile.of("thermometer"), Duration.ofSeconds(5)); // announced by plant
            Message reply = control.requestBlocking(Profile.of("thermometer"), new Text("read"));
            assertEquals(new Reading(19.5), reply.contents());
            assertTrue(controlNet.peer("plant").orElseThrow().connected());
        }
        // README example ends
    }
}
