package io.etherware.services.network;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.etherware.core.kernel.EtherwareNode;
import io.etherware.core.message.Profile;
import io.etherware.core.message.Text;
import java.nio.file.Path;
import java.time.Duration;
import org.junit.jupiter.api.Test;

/** The README's mutual-TLS example, verbatim between the markers, run with keys made as it says. */
class ReadmeTlsExampleIT {

    @Test
    void shouldRunTheReadmeTlsExample() throws Exception {
        TestPki pki = TestPki.deployment();
        pki.keyStore("plant");
        pki.keyStore("control");
        Path keys = pki.directory();
        char[] password = TestPki.PASSWORD;
        try (var plant = EtherwareNode.builder().nodeId("plant").build().start();
             var control = EtherwareNode.builder().nodeId("control").build().start()) {
            // README example begins
            // keys: the directory of the keytool steps above; password: from your secret store
            var plantNet = NetworkMessenger.start(plant, NetworkConfig.builder().listen("0.0.0.0", 0) // or a fixed port
                    .connectionFactory(ConnectionFactory.tls(keys.resolve("plant.p12"), password,
                            keys.resolve("trust.p12"), password))
                    .build());
            // README example ends
            try (plantNet;
                 var controlNet = NetworkMessenger.start(control, NetworkConfig.builder()
                         .connectionFactory(ConnectionFactory.tls(keys.resolve("control.p12"), password,
                                 keys.resolve("trust.p12"), password))
                         .peer("127.0.0.1", plantNet.localAddress().getPort()).build())) {
                plant.add(Profile.of("thermometer"), () -> (message, context) -> context.reply(message, new Text("19.5")));
                assertTrue(controlNet.awaitResolvable(Profile.of("thermometer"), Duration.ofSeconds(30)));
                assertEquals(new Text("19.5"), control.requestBlocking(Profile.of("thermometer"), new Text("read"))
                        .contents());
            }
        }
    }
}
