package io.etherware.deploy;

import io.etherware.deploy.internal.XmlElement;
import io.etherware.deploy.view.ViewConfig;
import io.etherware.services.management.AccessRule;
import io.etherware.services.management.ManagementConfig;
import io.etherware.services.network.ConnectionFactory;
import io.etherware.services.network.NetworkConfig;
import java.io.IOException;
import java.io.InputStream;
import java.net.InetSocketAddress;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.security.cert.CertificateException;
import java.security.cert.CertificateFactory;
import java.security.cert.X509Certificate;
import java.util.EnumSet;
import java.util.Set;

/**
 * The {@code <network>}, {@code <management>} and {@code <view>} sections of a deployment, as
 * configurations: addresses resolved, TLS key stores and signer certificates loaded (relative
 * paths against the deployment file's directory), every value checked by the configuration's own
 * rules. Used by one {@link DeploymentReader#read} call.
 */
final class NetworkSections {

    private final DeploymentReader.Place at;
    private final String nodeId;

    NetworkSections(DeploymentReader.Place at, String nodeId) {
        this.at = at;
        this.nodeId = nodeId;
    }

    NetworkConfig network(XmlElement element) throws DeploymentException {
        NetworkConfig.Builder builder = NetworkConfig.builder()
                .listen(address(element, "listen", element.attributes().get("listen")))
                .lanes(Integer.parseInt(element.attribute("lanes").orElse("2")))
                .insecure(DeploymentReader.flag(element, "insecure", false));
        for (XmlElement peer : element.children("peer")) {
            builder.peer(address(peer, "address", peer.attributes().get("address")));
        }
        if (element.attribute("cpus").isPresent()) {
            builder.threadCpus(DeploymentReader.cpus(at, element, "cpus"));
        }
        if (element.child("tls").isPresent()) {
            XmlElement tls = element.child("tls").orElseThrow();
            char[] keyPassword = password(tls, "keyStorePasswordFile");
            char[] trustPassword = password(tls, "trustStorePasswordFile");
            try {
                ConnectionFactory factory = ConnectionFactory.tls(resolve(tls.attributes().get("keyStore")),
                        keyPassword, resolve(tls.attributes().get("trustStore")), trustPassword);
                String named = factory.localNodeId().orElse(null);
                if (named != null && !named.equals(nodeId)) {
                    throw at.problem(tls, "<tls keyStore=\"" + tls.attributes().get("keyStore") + "\">: its"
                            + " certificate names node '" + named + "', but this is node '" + nodeId + "': a node's id"
                            + " is its certificate's CN; use that node's key store, or id=\"" + named + "\"");
                }
                builder.connectionFactory(factory);
            } catch (IOException e) {
                throw at.problem(tls, "<tls>: " + e.getMessage() + "; the stores are PKCS#12 (see the README's"
                        + " Security section for making them with keytool)");
            } finally {
                java.util.Arrays.fill(keyPassword, '\0');
                java.util.Arrays.fill(trustPassword, '\0');
            }
        }
        try {
            return builder.build();
        } catch (IllegalArgumentException | NullPointerException e) {
            throw at.problem(element, "<network>: " + e.getMessage() + (String.valueOf(e.getMessage()).contains(
                    "beyond loopback")
                    ? " (in this file: add <tls .../> to <network>, or insecure=\"true\" on a network you trust)"
                    : ""));
        }
    }

    ManagementConfig management(XmlElement element) throws DeploymentException {
        ManagementConfig.Builder builder = ManagementConfig.builder()
                .allowUnauthenticatedLinks(DeploymentReader.flag(element, "allowUnauthenticatedLinks", false));
        if (element.attribute("settleWait").isPresent()) {
            try {
                builder.settleWait(Durations.parse(element.attributes().get("settleWait")));
            } catch (IllegalArgumentException e) {
                throw at.problem(element, "<management settleWait=\"" + element.attributes().get("settleWait")
                        + "\">: " + e.getMessage());
            }
        }
        for (XmlElement allow : element.children("allow")) {
            Set<AccessRule.Operation> operations = EnumSet.noneOf(AccessRule.Operation.class);
            for (String operation : allow.attributes().get("operations").strip().split("\\s+")) {
                operations.add(AccessRule.Operation.valueOf(operation));
            }
            try {
                builder.allowRemote(allow.attributes().get("node"), operations, allow.attributes().get("components"));
            } catch (IllegalArgumentException e) {
                throw at.problem(allow, "<allow node=\"" + allow.attributes().get("node") + "\">: " + e.getMessage());
            }
        }
        for (XmlElement plugins : element.children("plugins")) {
            try {
                builder.allowDirectory(resolve(plugins.attributes().get("directory")));
            } catch (IllegalArgumentException e) {
                throw at.problem(plugins, "<plugins directory=\"" + plugins.attributes().get("directory") + "\">: "
                        + e.getMessage());
            }
            builder.trustedSigner(certificate(plugins, resolve(plugins.attributes().get("trustedSigner"))));
        }
        try {
            return builder.build();
        } catch (IllegalArgumentException e) {
            throw at.problem(element, "<management>: " + e.getMessage());
        }
    }

    Deployment.ViewPlan view(XmlElement element) throws DeploymentException {
        String listen = element.attributes().get("listen");
        boolean allowRemote = DeploymentReader.flag(element, "allowRemote", false);
        try {
            return new Deployment.ViewPlan(new ViewConfig(address(element, "listen", listen), allowRemote),
                    element.line());
        } catch (IllegalArgumentException e) {
            throw at.problem(element, "<view listen=\"" + listen + "\">: " + e.getMessage());
        }
    }

    private InetSocketAddress address(XmlElement element, String attribute, String text) throws DeploymentException {
        try {
            return HostPort.parse(text);
        } catch (IllegalArgumentException e) {
            throw at.problem(element, "<" + element.name() + " " + attribute + "=\"" + text + "\">: " + e.getMessage());
        }
    }

    /**
     * The password in {@code file}: its one line, without the line break.
     *
     * @throws IOException if the file cannot be read
     */
    static char[] readPassword(Path file) throws IOException {
        return Files.readString(file, StandardCharsets.UTF_8).stripTrailing().toCharArray();
    }

    private char[] password(XmlElement tls, String attribute) throws DeploymentException {
        Path file = resolve(tls.attributes().get(attribute));
        try {
            return readPassword(file);
        } catch (IOException e) {
            throw at.problem(tls, "<tls " + attribute + "=\"" + tls.attributes().get(attribute) + "\">: cannot read "
                    + file + " (" + e + "); the file holds the password on one line");
        }
    }

    private X509Certificate certificate(XmlElement plugins, Path file) throws DeploymentException {
        try (InputStream in = Files.newInputStream(file)) {
            return (X509Certificate) CertificateFactory.getInstance("X.509").generateCertificate(in);
        } catch (IOException | CertificateException | ClassCastException e) {
            throw at.problem(plugins, "<plugins trustedSigner=\"" + plugins.attributes().get("trustedSigner")
                    + "\">: " + file + " is not a readable X.509 certificate, PEM or DER (" + e.getMessage() + ")");
        }
    }

    private Path resolve(String path) {
        Path parent = at.file().toAbsolutePath().getParent();
        return parent == null ? Path.of(path) : parent.resolve(path);
    }
}
