// Avenues — the home saved-by-sweet-home-3d-7.sh3d beside this file, made by Sweet Home 3D
// itself (Debian's sweethome3d 7.0.2), so that tests read a home as Sweet Home writes it.
//
// It reads an example home of Sweet Home's own (Home.xml, as .ci/install-deps extracts
// them), adds what the examples lack, and saves the home with both entries, the serialized
// Java `Home` and `Home.xml`, as Sweet Home 3D 7 saves, with no model content (the models
// stay in Sweet Home's jar: furniture stands as boxes):
//  - a door mirrored (modelMirrored), and a door in a furniture group with a piece;
//  - a group inside a group, turned; the lists of both made by Arrays.asList (serialized
//    as java.util.Arrays$ArrayList, as a plugin may make them);
//  - a curved wall with a colour on each side, joined to a sloped wall (heightAtEnd);
//  - a level at the elevation of the first (elevationIndex), and a level that is not
//    viewable, each with a wall;
//  - a polyline, a dimension line and a label.
// Every object gets a fresh id (a UUID), so each run writes a different file.
//
//   apt-get download sweethome3d && dpkg -x sweethome3d_*.deb x
//   jar=x/usr/share/sweethome3d/sweethome3d.jar
//   javac -cp $jar SavedBySweetHome3D.java
//   java -Djava.awt.headless=true -cp $jar:. SavedBySweetHome3D \
//     /usr/local/share/avenues/sweethome3d-examples/2BedroomHouseWithBasement.xml saved-by-sweet-home-3d-7.sh3d
import com.eteks.sweethome3d.io.HomeFileRecorder;
import com.eteks.sweethome3d.io.HomeXMLHandler;
import com.eteks.sweethome3d.model.*;
import com.eteks.sweethome3d.tools.URLContent;
import java.io.File;
import java.util.*;
import javax.xml.parsers.SAXParserFactory;

public class SavedBySweetHome3D {
  public static void main(String[] args) throws Exception {
    // The examples name their icons and models as paths inside Sweet Home's jar.
    HomeXMLHandler handler = new HomeXMLHandler() {
      @Override
      protected Content parseContent(String element, Map<String, String> attributes, String name) throws org.xml.sax.SAXException {
        String path = attributes.get(name);
        java.net.URL url = path == null ? null : SavedBySweetHome3D.class.getResource("/" + path);
        return url != null ? new URLContent(url) : super.parseContent(element, attributes, name);
      }
    };
    SAXParserFactory.newInstance().newSAXParser().parse(new File(args[0]), handler);
    Home home = handler.getHome();
    Level base = home.getLevels().get(0);

    List<HomePieceOfFurniture> doors = new ArrayList<>(), others = new ArrayList<>();
    for (HomePieceOfFurniture p : home.getFurniture()) (p instanceof HomeDoorOrWindow ? doors : others).add(p);
    ((HomeDoorOrWindow) doors.get(0)).setModelMirrored(true);
    List<HomePieceOfFurniture> withDoor = Arrays.asList(doors.get(1), others.get(0));
    for (HomePieceOfFurniture p : withDoor) home.deletePieceOfFurniture(p);
    home.addPieceOfFurniture(new HomeFurnitureGroup(withDoor, "group with a door"));
    List<HomePieceOfFurniture> pair = Arrays.asList(others.get(1), others.get(2));
    for (HomePieceOfFurniture p : pair) home.deletePieceOfFurniture(p);
    home.deletePieceOfFurniture(others.get(3));
    HomeFurnitureGroup outer = new HomeFurnitureGroup(Arrays.asList(new HomeFurnitureGroup(pair, "inner"), others.get(3)), "outer");
    outer.setAngle(0.3f);
    home.addPieceOfFurniture(outer);

    Wall arc = new Wall(2000, 0, 2600, 0, 12, 250);
    arc.setArcExtent(1.2f);
    arc.setLeftSideColor(0xFF0000);
    arc.setRightSideColor(0x00FF00);
    Wall slope = new Wall(2600, 0, 2600, 500, 15, 100);
    slope.setHeightAtEnd(240f);
    arc.setWallAtEnd(slope);
    slope.setWallAtStart(arc);
    home.addWall(arc);  // Home.addWall puts a wall on the selected level: its level is set after
    home.addWall(slope);
    arc.setLevel(base);
    slope.setLevel(base);

    Level same = new Level("same elevation", base.getElevation(), base.getFloorThickness(), base.getHeight());
    same.setElevationIndex(base.getElevationIndex() + 1);
    home.addLevel(same);
    Wall onSame = new Wall(3000, 0, 3400, 0, 10, 200);
    home.addWall(onSame);
    onSame.setLevel(same);
    Level hidden = new Level("hidden", base.getElevation() + 1000, 12, 250);
    hidden.setViewable(false);
    home.addLevel(hidden);
    Wall onHidden = new Wall(3000, 100, 3400, 100, 10, 200);
    home.addWall(onHidden);
    onHidden.setLevel(hidden);

    Polyline polyline = new Polyline(new float[][] {{0, -100}, {300, -100}, {300, -200}});
    home.addPolyline(polyline);
    polyline.setLevel(base);
    DimensionLine dimension = new DimensionLine(0, -300, 400, -300, 20);
    home.addDimensionLine(dimension);
    dimension.setLevel(base);
    Label label = new Label("a label", 100, -400);
    home.addLabel(label);
    label.setLevel(base);

    // Compressed, temporary content only (no model copied in), both entries.
    new HomeFileRecorder(9, true, null, false, true).writeHome(home, args[1]);
  }
}
